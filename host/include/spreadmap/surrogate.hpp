// Surrogate models: host-only classes behind the C descriptor. The host owns names, units, splits
// and files; a plugin sees standard matrices (row-major) and keeps its own normalisation in its state.
#pragma once
#include <spreadmap/abi.h>
#include <spreadmap/plugin.hpp>

extern "C" {
typedef struct sm_dataset_v1 {
  uint32_t rows, n_in, n_out;
  const double *x;  // rows x n_in
  const double *y;  // rows x n_out
  // rows x n_out, or NULL: the variance of each y that is known beforehand (y the mean of replicated
  // runs: their scatter^2 / count), 0 where unknown. A model may add it to its own noise; it may ignore it.
  const double *noise_var;
} sm_dataset_v1;

typedef struct sm_surrogate_ops_v1 {
  int has_std;                                                        // 1 when predict() fills a standard deviation
  int (*fit)(void *self, const sm_dataset_v1 *train, sm_error *err);  // 0 on success
  // mean: rows x n_out; std: rows x n_out or NULL. 0 on success.
  int (*predict)(const void *self, uint32_t rows, const double *x, double *mean, double *std, sm_error *err);
  // JSON text of the fitted state (weights or hyperparameters, normalisation); valid until the next call.
  const char *(*save)(void *self);
  int (*load)(void *self, const char *state_json, sm_error *err);  // 0 on success
  // JSON text with facts about the last fit (final loss, epochs, hyperparameters). A model that fits
  // scales per output gives them as {"outputs": [{"signal_std": s, "noise_std": n}, ...]} in the
  // output's units; the host's train report shows them.
  const char *(*fit_info)(void *self);
  int takes_noise_var;  // 1 when fit() uses sm_dataset_v1::noise_var (0: it is ignored)
} sm_surrogate_ops_v1;
}
