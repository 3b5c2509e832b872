// With CUDA in the build, every contact and spreader plugin carries its GPU kernels: the descriptor
// says cpu + cuda, the CUDA entry point is exported and agrees with the CPU table, and the static CUDA
// runtime inside stays hidden (the module's C exports are its two entry points). A module built
// without CUDA, asked for its GPU kernels, is a PluginError saying how to fix it. Without a device,
// launching a real plugin's kernel is a clean RunFailure in CUDA's own words, not a crash.
#include <gtest/gtest.h>
#include <spreadmap/contact.hpp>

#include <cstdio>
#include <memory>
#include <string>

#include "core/error.hpp"
#include "core/registry.hpp"
#include "cuda/backend.hpp"
#include "cuda/plugin_kernels.hpp"
#include "gpu/plugin_params.hpp"
#include "unit/built_plugins.hpp"
#include "verification/contact_laws.hpp"

namespace sm = spreadmap;
namespace fs = std::filesystem;

namespace {

sm::PluginRegistry &registry() { return built_plugins(); }

// The C symbols a module exports (nm -D --defined-only), sorted, one per line. C++ symbols (_Z...) are
// left out: libstdc++'s unique template statics are exported by every module, CUDA or not.
std::string exported_c_symbols(const fs::path &file) {
  std::string out;
  const std::string command = "nm -D --defined-only '" + file.string() + "' 2>/dev/null";
  std::unique_ptr<FILE, int (*)(FILE *)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) return out;
  char line[1024];
  while (std::fgets(line, sizeof line, pipe.get())) {
    std::string s = line;
    s = s.substr(s.find_last_of(' ') + 1);
    if (s.rfind("_Z", 0) != 0) out += s;
  }
  return out;
}

// A plugin's name as the test parameter; printed bare, it ends the CTest name.
struct Name {
  const char *text;
  operator std::string() const { return text; }
};
void PrintTo(const Name &n, std::ostream *os) { *os << n.text; }

std::vector<Name> contact_plugins() {
  std::vector<Name> names;
  for (const char *name : sm::test::ContactLaws::names()) names.push_back({name});
  return names;
}

class CudaContactPlugin : public ::testing::TestWithParam<Name> {};
class CudaSpreaderPlugin : public ::testing::TestWithParam<Name> {};

TEST_P(CudaContactPlugin, CarriesKernelsThatMatchItsCpuTable) {
  const auto &plugin = registry().get("contact", std::string(GetParam()));
  EXPECT_EQ(plugin.descriptor->backends, SM_BACKEND_CPU | SM_BACKEND_CUDA);
  const auto kernels = sm::cuda::contact_kernels(plugin);
  ASSERT_NE(kernels.ops, nullptr);
  EXPECT_EQ(kernels.ops->abi, SPREADMAP_CUDA_ABI);
  // The CPU table counts the most an instance keeps, the rolling spring's 3 values included (CPU only).
  EXPECT_EQ(kernels.ops->history + 3, static_cast<const sm::sm_contact_ops_v1 *>(plugin.descriptor->ops)->history);
  EXPECT_EQ(kernels.id, "contact/" + std::string(GetParam()));
  EXPECT_EQ(exported_c_symbols(plugin.file), "sm_contact_cuda_v1\nspreadmap_plugin_v1\n");  // no cuda* leaks
}

TEST_P(CudaSpreaderPlugin, CarriesKernels) {
  const auto &plugin = registry().get("spreader", std::string(GetParam()));
  EXPECT_EQ(plugin.descriptor->backends, SM_BACKEND_CPU | SM_BACKEND_CUDA);
  const auto kernels = sm::cuda::spreader_kernels(plugin);
  ASSERT_NE(kernels.ops, nullptr);
  EXPECT_EQ(kernels.ops->abi, SPREADMAP_CUDA_ABI);
  EXPECT_EQ(exported_c_symbols(plugin.file), "sm_spreader_cuda_v1\nspreadmap_plugin_v1\n");
}

INSTANTIATE_TEST_SUITE_P(InTree, CudaContactPlugin, ::testing::ValuesIn(contact_plugins()));
INSTANTIATE_TEST_SUITE_P(InTree, CudaSpreaderPlugin, ::testing::Values(Name{"roller"}, Name{"blade"}));

TEST(CudaPlugins, APluginBuiltWithoutCudaIsRefusedWithTheFix) {
  const auto &plugin = registry().load_file(SPREADMAP_CPU_ONLY_MODULE, "contact");
  EXPECT_EQ(plugin.descriptor->backends, SM_BACKEND_CPU);
  try {
    sm::cuda::contact_kernels(plugin);
    FAIL() << "a CPU-only module was accepted for the GPU";
  } catch (const sm::PluginError &e) {
    const std::string text = e.what();
    EXPECT_NE(text.find("contact/cpu_only_spring cannot run on the GPU"), std::string::npos) << text;
    EXPECT_NE(text.find("built without CUDA"), std::string::npos) << text;
    EXPECT_NE(text.find("SPREADMAP_ENABLE_CUDA=ON"), std::string::npos) << text;
    EXPECT_NE(text.find("scene.backend: cpu"), std::string::npos) << text;
  }
}

TEST(CudaPlugins, AContactPluginIsNotASpreader) {
  const auto &plugin = registry().get("contact", "hooke_slider");
  EXPECT_THROW(sm::cuda::spreader_kernels(plugin), sm::PluginError);
}

TEST(CudaPlugins, LaunchingWithoutADeviceIsACleanRunFailure) {
  if (sm::cuda::device_count() > 0) GTEST_SKIP() << "a CUDA device is present (tests/gpu covers launches)";
  const auto &plugin = registry().get("contact", "hooke_slider");
  const auto kernels = sm::cuda::contact_kernels(plugin);
  const sm::PluginInstance law(plugin, sm::test::plugin_params(plugin.descriptor));
  sm::Particles<double> p{};
  sm::PairList<double> list{};
  try {
    sm::cuda::launch_pairs(kernels, law.get(), p, list);
    FAIL() << "a launch without a device succeeded";
  } catch (const sm::RunFailure &e) {
    const std::string text = e.what();
    EXPECT_NE(text.find("contact/hooke_slider on the GPU"), std::string::npos) << text;
    EXPECT_NE(text.find("CUDA says"), std::string::npos) << text;
  }
}

}  // namespace
