// A deliberately faulty plugin for the registry tests, compiled once per fault (tests/unit/core.cmake):
//   FIXTURE_KIND, FIXTURE_NAME   what the descriptor claims (default: contact / the file's name)
//   FIXTURE_ABI                  the ABI number it reports (default: the SDK's)
//   FIXTURE_NO_ENTRY             exports a differently named function instead of the entry point
//   FIXTURE_ENTRY_VARIABLE       exports the entry point's name as a variable, not a function
//   FIXTURE_NULL_DESCRIPTOR      the entry point returns NULL
//   FIXTURE_FACTORY              0: create() works; 1: it refuses through sm_error; 2: it throws
//   FIXTURE_VERSION              the plugin's version text (tells two copies apart)
// Its schema takes the keys of the quick preset's contact and substrate sections, so a workflow can
// select it as its contact law and pass validation; ops is NULL, so it must never reach a simulation.
#include <spreadmap/abi.h>
#include <spreadmap/params.hpp>

#include <cstdio>
#include <stdexcept>

#ifndef FIXTURE_KIND
#define FIXTURE_KIND "contact"
#endif
#ifndef FIXTURE_ABI
#define FIXTURE_ABI SPREADMAP_PLUGIN_ABI
#endif
#ifndef FIXTURE_FACTORY
#define FIXTURE_FACTORY 0
#endif
#ifndef FIXTURE_VERSION
#define FIXTURE_VERSION "1.0.0"
#endif

namespace {

namespace sm = spreadmap;

constexpr sm_param_v1 params[] = {
    sm::number("v_max", "m/s", 1e-6, 100, 0.5, "largest expected impact speed"),
    sm::number("overlap_max", "m", 1e-9, 1e-3, 5e-6, "overlap at v_max"),
    sm::number("friction", "-", 0, 10, 0.5, "mu: sliding friction"),
    sm::number("restitution", "-", 0, 1, 0.8, "epsilon: normal restitution"),
};

void *create(const char *, sm_error *err) {
#if FIXTURE_FACTORY == 1
  err->code = 1;
  std::snprintf(err->text, sizeof err->text, "%s", "fixture refuses every parameter set");
  return nullptr;
#elif FIXTURE_FACTORY == 2
  (void)err;
  throw std::runtime_error("fixture factory always throws");
#else
  (void)err;
  return new int(42);
#endif
}

void destroy(void *self) { delete static_cast<int *>(self); }

[[maybe_unused]] const sm_plugin_v1 descriptor = {FIXTURE_ABI,
                                                  FIXTURE_KIND,
                                                  FIXTURE_NAME,
                                                  FIXTURE_VERSION,
                                                  "registry test fixture",
                                                  params,
                                                  sizeof params / sizeof params[0],
                                                  SM_BACKEND_CPU,
                                                  &create,
                                                  &destroy,
                                                  nullptr};

}  // namespace

#ifdef FIXTURE_NO_ENTRY
extern "C" SM_EXPORT const sm_plugin_v1 *some_other_function(void) { return &descriptor; }
#elif defined(FIXTURE_ENTRY_VARIABLE)
extern "C" {
SM_EXPORT const sm_plugin_v1 *spreadmap_plugin_v1 = &descriptor;  // data: calling it would crash
}
#elif defined(FIXTURE_NULL_DESCRIPTOR)
extern "C" SM_EXPORT const sm_plugin_v1 *spreadmap_plugin_v1(void) { return nullptr; }
#else
extern "C" SM_EXPORT const sm_plugin_v1 *spreadmap_plugin_v1(void) { return &descriptor; }
#endif
