#include "core/error.hpp"
#include "workflow/stage.hpp"

namespace spreadmap {
namespace {
class Pending : public Stage {
 public:
  void validate(const Workflow &, const StageEntry &, const nlohmann::json &, PluginRegistry &, Diagnostics &) override {}
  void run(StageContext &) override { throw RunFailure("the map stage is not built yet"); }
};
}  // namespace
std::unique_ptr<Stage> make_map_stage() { return std::make_unique<Pending>(); }
}  // namespace spreadmap
