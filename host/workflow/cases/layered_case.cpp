#include "workflow/cases/layered_case.hpp"

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "core/files.hpp"
#include "engine/vtp_io.hpp"
#include "workflow/cases/case_record.hpp"
#include "workflow/cases/layers.hpp"

namespace spreadmap {

std::optional<engine::ParticleSet> finished_layer(const fs::path &dir, const std::string &hash,
                                                  const std::string &name) {
  if (!record_finished(dir, "layer.json", hash)) return std::nullopt;
  spdlog::info("{}: finished before, read back", name);
  return engine::read_vtp(dir / "state.vtp").particles;
}

nlohmann::json finish_layered_case(const CaseRequest &req, const std::string &hash, const nlohmann::json &layers,
                                   const nlohmann::json &extra) {
  write_atomic(req.dir / "state.vtp", read_text(req.dir / layer_folder(int(layers.size())) / "state.vtp"));
  const nlohmann::json &last = layers.back();
  std::size_t removed = 0;
  double steps = 0;
  for (const auto &l : layers) {
    for (const char *key : {"removed", "removed_settling", "removed_strokes"}) removed += l.value(key, std::size_t(0));
    steps += l.value("steps", 0.0);
  }
  nlohmann::json out = {{"id", req.id},
                        {"hash", hash},
                        {"status", "done"},
                        {"inputs", req.inputs},
                        {"layers", layers},
                        {"removed", removed},
                        {"steps", steps},
                        {"simulated_time", last["simulated_time"]},
                        {"particle_steps_per_second", last.value("particle_steps_per_second", 0.0)},  // the last pass's
                        {"precision", precision_name(req.scene.precision)},
                        {"spreader", last["spreader"]},
                        {"spreader_end", last["spreader_end"]}};
  out.update(extra);
  return write_finished_record(req.dir, "case.json", out);
}

}  // namespace spreadmap
