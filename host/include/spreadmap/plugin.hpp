// The one macro every plugin ends with: it builds the C descriptor from a C++ class.
//
//   SPREADMAP_PLUGIN(kind, Class, "name", "1.0.0", "summary", ops_table)
//
// Class must provide `static constexpr sm_param_v1 params[]` and `static Class bind(const sm::Values&)`
// (host side, may throw sm::ParamError). create() copies the bound object to the heap; destroy()
// deletes it. Exceptions never cross the boundary: they become sm_error text.
#pragma once
#include <spreadmap/abi.h>
#include <spreadmap/params.hpp>

#include <cstdio>
#include <exception>
#include <new>

namespace spreadmap::detail {

inline void set_error(sm_error *err, const char *what) {
  if (!err) return;
  err->code = 1;
  std::snprintf(err->text, sizeof err->text, "%s", what);
}

template <class Class> void *create(const char *params_json, sm_error *err) {
  try {
    return new Class(Class::bind(Values::parse(params_json)));
  } catch (const std::exception &e) {
    set_error(err, e.what());
  } catch (...) {
    set_error(err, "unknown exception while binding parameters");
  }
  return nullptr;
}
template <class Class> void destroy(void *self) { delete static_cast<Class *>(self); }

}  // namespace spreadmap::detail

#ifndef SPREADMAP_BACKENDS
#define SPREADMAP_BACKENDS SM_BACKEND_CPU
#endif

#define SPREADMAP_PLUGIN(KIND, CLASS, NAME, VERSION, SUMMARY, OPS)                                                   \
  extern "C" SM_EXPORT const sm_plugin_v1 *spreadmap_plugin_v1(void) {                                               \
    static const sm_plugin_v1 descriptor = {SPREADMAP_PLUGIN_ABI,                                                    \
                                            KIND,                                                                    \
                                            NAME,                                                                    \
                                            VERSION,                                                                 \
                                            SUMMARY,                                                                 \
                                            CLASS::params,                                                           \
                                            static_cast<uint32_t>(sizeof(CLASS::params) / sizeof(CLASS::params[0])), \
                                            SPREADMAP_BACKENDS,                                                      \
                                            &::spreadmap::detail::create<CLASS>,                                     \
                                            &::spreadmap::detail::destroy<CLASS>,                                    \
                                            OPS};                                                                    \
    return &descriptor;                                                                                              \
  }
