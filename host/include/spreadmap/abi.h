/* spreadmap plugin ABI (its versions: docs/plugins.md, "The plugin ABI"). Plain C:
 * nothing C++ crosses a shared-library boundary. Every plugin exports exactly one symbol, `spreadmap_plugin_v1`,
 * returning a pointer to a static descriptor whose first field is the ABI version; the host checks it before
 * touching anything else.
 *
 * The version is major.minor. A minor version only appends fields at the end of an ops table, so a host loads
 * every plugin of its major version up to its own minor and reads only the fields the plugin's minor has; a
 * change of anything already there is a new major version. A plugin may target an older minor
 * (SPREADMAP_TARGET_ABI_MINOR) to load into older hosts; its tables then end where that minor's did. */
#ifndef SPREADMAP_ABI_H
#define SPREADMAP_ABI_H
#include <stddef.h>
#include <stdint.h>

#define SPREADMAP_PLUGIN_ABI_MAJOR 10u
#define SPREADMAP_PLUGIN_ABI_MINOR 4u
#ifndef SPREADMAP_TARGET_ABI_MINOR
#define SPREADMAP_TARGET_ABI_MINOR SPREADMAP_PLUGIN_ABI_MINOR
#endif
/* The descriptor's `abi` field: major in the high 16 bits, minor in the low (ABI 9 and older: a plain count). */
#define SPREADMAP_ABI_VERSION(MAJOR, MINOR) (((MAJOR) << 16) | (MINOR))
#define SPREADMAP_PLUGIN_ABI SPREADMAP_ABI_VERSION(SPREADMAP_PLUGIN_ABI_MAJOR, SPREADMAP_TARGET_ABI_MINOR)

#if defined(_WIN32)
#define SM_EXPORT __declspec(dllexport)
#else
#define SM_EXPORT __attribute__((visibility("default")))
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* An error reported by a plugin: code != 0 and a sentence in text. */
typedef struct sm_error {
  int code;
  char text[1024];
} sm_error;

/* Parameter types of a schema entry. */
typedef enum sm_param_type {
  SM_NUMBER = 0,  /* real number with a physical dimension given by `unit` (SI) */
  SM_INTEGER = 1, /* whole number, range [min, max] */
  SM_BOOLEAN = 2, /* true / false */
  SM_ENUM = 3,    /* one of `choices` ("a|b|c"); default in `def_text` */
  SM_STRING = 4,  /* free text; default in `def_text` */
  SM_TABLE = 5    /* nested mapping or list, passed through as JSON; validated by the plugin */
} sm_param_type;

/* One entry of a plugin's parameter schema. Values reach the plugin validated and in SI. */
typedef struct sm_param_v1 {
  const char *name; /* snake_case key as written in a workflow */
  sm_param_type type;
  const char *unit;     /* SI unit of a number ("m", "m/s", "kg/m^3", "1/s", "-" dimensionless) */
  double min, max;      /* inclusive range for numbers and integers */
  double def;           /* default for numbers, integers and booleans (0/1) */
  const char *def_text; /* default for enums and strings; NULL otherwise */
  int required;         /* 1: no default, the user must give it */
  const char *choices;  /* enums: "sigmoid|tanh|atan"; NULL otherwise */
  const char *doc;      /* one line: symbol and meaning */
} sm_param_v1;

/* Backends a plugin build contains. */
#define SM_BACKEND_CPU 1u
#define SM_BACKEND_CUDA 2u

typedef struct sm_plugin_v1 {
  uint32_t abi;        /* SPREADMAP_PLUGIN_ABI: the version the plugin was built for */
  const char *kind;    /* "contact" | "spreader" | "metrics" | "surrogate" */
  const char *name;    /* equals the folder name and the .so stem */
  const char *version; /* the plugin's own version, "1.0.0" */
  const char *summary; /* one line */
  const sm_param_v1 *params;
  uint32_t n_params;
  uint32_t backends; /* SM_BACKEND_* bits */
  /* Makes an instance from validated SI parameters as a JSON object text. Returns NULL and fills
   * err on failure (cross-parameter constraints). The instance is freed by destroy(). */
  void *(*create)(const char *params_json, sm_error *err);
  void (*destroy)(void *self);
  const void *ops; /* the kind's table: sm_contact_ops_v1, sm_spreader_ops_v2, ... */
} sm_plugin_v1;

typedef const sm_plugin_v1 *(*sm_plugin_entry_v1)(void);

#ifdef __cplusplus
}
#endif
#endif
