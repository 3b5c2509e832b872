#include "cuda/plugin_kernels.hpp"

#include <dlfcn.h>
#include <spreadmap/contact.hpp>

#include <type_traits>

#include "core/error.hpp"

namespace spreadmap::cuda {
namespace {

// The registry keeps the module loaded; RTLD_NOLOAD only looks it up (and never loads a second copy).
void *entry_point(const LoadedPlugin &plugin, const char *symbol) {
  const std::string file = fs::absolute(plugin.file).string();
  void *handle = dlopen(file.c_str(), RTLD_LAZY | RTLD_NOLOAD);
  if (!handle)
    throw PluginError(plugin.id() + ": " + file + " is not loaded; load it through the registry first");
  void *entry = dlsym(handle, symbol);
  dlclose(handle);  // drops only the reference taken above
  if (!entry || !(plugin.descriptor->backends & SM_BACKEND_CUDA))
    throw PluginError(plugin.id() + " cannot run on the GPU: " + file +
                      " was built without CUDA kernels (no entry point '" + symbol +
                      "')\n  rebuild it with SPREADMAP_ENABLE_CUDA=ON (nvcc installed), or set scene.backend: cpu");
  return entry;
}

void check_abi(const LoadedPlugin &plugin, const void *ops, std::uint32_t abi) {
  if (!ops) throw PluginError(plugin.id() + ": its CUDA entry point returned no table");
  if (abi != SPREADMAP_CUDA_ABI)
    throw PluginError(plugin.id() + " has CUDA kernels of ABI " + std::to_string(abi) +
                      ", this host needs " + std::to_string(SPREADMAP_CUDA_ABI) + ": rebuild it with this SDK");
}

void raise(const std::string &id, const sm_error &err) {
  throw RunFailure(id +
                   " on the GPU: " + (err.text[0] ? err.text : "the kernel launch failed without saying why"));
}

}  // namespace

ContactKernels contact_kernels(const LoadedPlugin &plugin) {
  if (std::string(plugin.descriptor->kind) != "contact")
    throw PluginError(plugin.id() + " is not a contact plugin");
  const auto entry = reinterpret_cast<sm_contact_cuda_entry_v1>(entry_point(plugin, SPREADMAP_CONTACT_CUDA_ENTRY));
  const sm_contact_cuda_ops_v1 *ops = entry();
  check_abi(plugin, ops, ops ? ops->abi : 0);
  return {plugin.id(), ops};
}

GeometryKernels spreader_kernels(const LoadedPlugin &plugin) {
  if (std::string(plugin.descriptor->kind) != "spreader")
    throw PluginError(plugin.id() + " is not a spreader plugin");
  const auto entry = reinterpret_cast<sm_spreader_cuda_entry_v1>(entry_point(plugin, SPREADMAP_SPREADER_CUDA_ENTRY));
  const sm_geometry_cuda_ops_v1 *ops = entry();
  check_abi(plugin, ops, ops ? ops->abi : 0);
  return {plugin.id(), ops};
}

template <class Real>
void launch_pairs(const ContactKernels &k, const void *law, const Particles<Real> &p, const PairList<Real> &list,
                  int device, void *stream) {
  sm_error err{0, {0}};
  const sm_cuda_launch_v1 at{device, stream};
  int rc;
  if constexpr (std::is_same_v<Real, double>) rc = k.ops->pairs_f64(law, &p, &list, &at, &err);
  else rc = k.ops->pairs_f32(law, &p, &list, &at, &err);
  if (rc) raise(k.id, err);
}

template <class Real>
void launch_walls(const ContactKernels &k, const void *law, const Particles<Real> &p, const WallContacts<Real> &w,
                  int device, void *stream) {
  sm_error err{0, {0}};
  const sm_cuda_launch_v1 at{device, stream};
  int rc;
  if constexpr (std::is_same_v<Real, double>) rc = k.ops->walls_f64(law, &p, &w, &at, &err);
  else rc = k.ops->walls_f32(law, &p, &w, &at, &err);
  if (rc) raise(k.id, err);
}

template <class Real>
void launch_geometry(const GeometryKernels &k, const void *geometry, const Particles<Real> &p,
                     const WallContacts<Real> &w, int device, void *stream) {
  sm_error err{0, {0}};
  const sm_cuda_launch_v1 at{device, stream};
  int rc;
  if constexpr (std::is_same_v<Real, double>) rc = k.ops->contacts_f64(geometry, &p, &w, &at, &err);
  else rc = k.ops->contacts_f32(geometry, &p, &w, &at, &err);
  if (rc) raise(k.id, err);
}

template void launch_pairs<double>(const ContactKernels &, const void *, const Particles<double> &,
                                   const PairList<double> &, int, void *);
template void launch_pairs<float>(const ContactKernels &, const void *, const Particles<float> &,
                                  const PairList<float> &, int, void *);
template void launch_walls<double>(const ContactKernels &, const void *, const Particles<double> &,
                                   const WallContacts<double> &, int, void *);
template void launch_walls<float>(const ContactKernels &, const void *, const Particles<float> &,
                                  const WallContacts<float> &, int, void *);
template void launch_geometry<double>(const GeometryKernels &, const void *, const Particles<double> &,
                                      const WallContacts<double> &, int, void *);
template void launch_geometry<float>(const GeometryKernels &, const void *, const Particles<float> &,
                                     const WallContacts<float> &, int, void *);

}  // namespace spreadmap::cuda
