#include "core/registry.hpp"
#include "core/plugin_abi.hpp"

#include <dlfcn.h>
#include <link.h>
#include <spdlog/spdlog.h>

#include <boost/dll/runtime_symbol_info.hpp>
#include <boost/dll/shared_library.hpp>
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <set>

#include "core/error.hpp"
#include "core/suggest.hpp"

namespace spreadmap {

std::string LoadedPlugin::id() const { return std::string(descriptor->kind) + "/" + descriptor->name; }

PluginRegistry::PluginRegistry(std::vector<fs::path> roots) : roots_(std::move(roots)) {}
PluginRegistry::~PluginRegistry() = default;

std::vector<fs::path> PluginRegistry::default_roots() {
  std::vector<fs::path> roots;
  if (const char *env = std::getenv("SPREADMAP_PLUGIN_PATH")) {
    std::string s = env;
    std::size_t pos = 0;
    while (pos <= s.size()) {
      const std::size_t next = s.find(':', pos);
      const std::string part = s.substr(pos, next == std::string::npos ? std::string::npos : next - pos);
      if (!part.empty()) roots.emplace_back(part);
      if (next == std::string::npos) break;
      pos = next + 1;
    }
  }
  const fs::path exe = boost::dll::program_location().string();
  roots.push_back(exe.parent_path().parent_path() / "lib" / "spreadmap" / "plugins");
  return roots;
}

PluginRegistry &PluginRegistry::global() {
  static PluginRegistry registry(default_roots());
  return registry;
}

std::vector<fs::path> PluginRegistry::candidates(const std::string &kind, const std::string &name) const {
  std::vector<fs::path> found;
  for (const auto &root : roots_)
    for (const fs::path &p : {root / kind / (name + ".so"), root / (name + ".so")}) {
      std::error_code ec;
      if (fs::is_regular_file(p, ec)) found.push_back(p);
    }
  return found;
}

std::vector<std::string> PluginRegistry::names(const std::string &kind) const {
  std::set<std::string> out;
  for (const auto &root : roots_) {
    std::error_code ec;
    const fs::path dir = root / kind;
    if (!fs::is_directory(dir, ec)) continue;
    for (const auto &entry : fs::directory_iterator(dir, ec))
      if (entry.path().extension() == ".so") out.insert(entry.path().stem().string());
  }
  return {out.begin(), out.end()};
}

namespace {
// True when `address` lies in an executable segment of a loaded object: a function's code, not data
// (a plugin that exports its entry point's name as a variable would make the call jump into data).
bool in_executable_segment(const void *address) {
  struct Query {
    std::uintptr_t address;
    bool executable = false;
  } query{reinterpret_cast<std::uintptr_t>(address)};
  ::dl_iterate_phdr(
      [](dl_phdr_info *info, std::size_t, void *data) {
        auto &q = *static_cast<Query *>(data);
        for (int i = 0; i < info->dlpi_phnum; ++i) {
          const auto &segment = info->dlpi_phdr[i];
          const std::uintptr_t begin = info->dlpi_addr + segment.p_vaddr;
          if (segment.p_type == PT_LOAD && q.address >= begin && q.address < begin + segment.p_memsz) {
            q.executable = (segment.p_flags & PF_X) != 0;
            return 1;
          }
        }
        return 0;
      },
      &query);
  return query.executable;
}
}  // namespace

const LoadedPlugin &PluginRegistry::load_file(const fs::path &file, const std::string &expected_kind) {
  const std::string key = fs::absolute(file).lexically_normal().string();
  if (auto it = loaded_.find(key); it != loaded_.end()) return it->second;
  auto lib = std::make_shared<boost::dll::shared_library>();
  boost::dll::fs::error_code ec;
  lib->load(boost::dll::fs::path(file.string()), boost::dll::load_mode::rtld_lazy | boost::dll::load_mode::rtld_local,
            ec);
  if (ec)
    throw PluginError("cannot load plugin " + file.string() + ": " + ec.message() +
                      "\n  is it a shared library built for this machine? rebuild it with this SDK");
  if (!lib->has("spreadmap_plugin_v1"))
    throw PluginError(file.string() +
                      " is not a spreadmap plugin: it has no entry point 'spreadmap_plugin_v1'\n"
                      "  plugins end with SPREADMAP_PLUGIN(...) or SPREADMAP_CONTACT_PLUGIN(...) and build with "
                      "spreadmap_add_plugin()");
  if (!in_executable_segment(::dlsym(lib->native(), "spreadmap_plugin_v1")))
    throw PluginError(file.string() +
                      " exports 'spreadmap_plugin_v1' as data, not as a function: calling it would crash; the "
                      "entry point is the function SPREADMAP_PLUGIN(...) defines: rebuild it with this SDK");
  const auto entry = lib->get<const sm_plugin_v1 *()>("spreadmap_plugin_v1");
  const sm_plugin_v1 *d = entry();
  if (!d) throw PluginError(file.string() + ": its entry point returned no descriptor");
  if (const std::string refusal = abi_refusal(d->abi); !refusal.empty())
    throw PluginError(file.string() + " " + refusal);
  const std::string stem = file.stem().string();
  if (!expected_kind.empty() && expected_kind != d->kind)
    throw PluginError(file.string() + " is a " + d->kind + " plugin, found where " + expected_kind +
                      " plugins are searched: move it to a " + d->kind + "/ folder");
  if (stem != d->name)
    throw PluginError(file.string() + " registers the name '" + d->name +
                      "', which differs from its file name: the .so stem and the registered name must be equal");
  libraries_.push_back(lib);
  return loaded_.emplace(key, LoadedPlugin{d, file}).first->second;
}

const LoadedPlugin &PluginRegistry::get(const std::string &kind, const std::string &name) {
  const std::string id = kind + "/" + name;
  if (auto it = loaded_.find(id); it != loaded_.end()) return it->second;
  // By name only: a name that is a path would load a library from anywhere a workflow points to.
  const bool plain = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  });
  if (!plain)
    throw PluginError("'" + name + "' is not a plugin name: " + kind +
                      " plugins are chosen by name (letters, digits, _ and -), never by a path; install the "
                      "library in a plugin folder or add its folder to SPREADMAP_PLUGIN_PATH, then use its name");
  const auto files = candidates(kind, name);
  if (files.empty()) {
    const auto available = names(kind);
    std::string msg = "unknown " + kind + " plugin '" + name + "'";
    const std::string near = closest(name, available);
    std::string roots;
    for (const auto &r : roots_) roots += (roots.empty() ? "" : ", ") + (r / kind).string();
    msg += "\n  " + (near.empty() ? std::string() : "did you mean '" + near + "'? ") +
           "available: " + (available.empty() ? std::string("none") : join(available)) + " (searched " + roots + ")";
    throw PluginError(msg);
  }
  const LoadedPlugin &p = load_file(files.front(), kind);
  for (std::size_t i = 1; i < files.size(); ++i)
    spdlog::info("{} from {} shadows {}", id, files.front().string(), files[i].string());
  return loaded_.emplace(id, p).first->second;
}

PluginInstance::PluginInstance(const LoadedPlugin &plugin, const std::string &params_json, const std::string &where)
    : plugin_(&plugin) {
  sm_error err{0, {0}};
  const std::string prefix = (where.empty() ? std::string() : where + ": ") + plugin.id() + ": ";
  // The ABI says create() reports through err, but a hand-written factory may still throw: the
  // exception must become the same clear error, not terminate the host.
  try {
    self_ = plugin.descriptor->create(params_json.c_str(), &err);
  } catch (const std::exception &e) {
    throw PluginError(prefix + "its factory threw instead of reporting an error: " + e.what());
  } catch (...) {
    throw PluginError(prefix + "its factory threw an unknown exception");
  }
  if (!self_) throw PluginError(prefix + (err.code ? err.text : "create() failed without saying why"));
}

PluginInstance &PluginInstance::operator=(PluginInstance &&o) noexcept {
  if (this != &o) {
    if (self_) plugin_->descriptor->destroy(self_);
    plugin_ = o.plugin_;
    self_ = o.self_;
    o.self_ = nullptr;
  }
  return *this;
}

PluginInstance::~PluginInstance() {
  if (self_) plugin_->descriptor->destroy(self_);
}

}  // namespace spreadmap
