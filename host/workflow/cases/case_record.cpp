#include "workflow/cases/case_record.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/files.hpp"
#include "workflow/cases/case_runner.hpp"

namespace spreadmap {

nlohmann::json write_finished_record(const fs::path &dir, const std::string &record_name, nlohmann::json record) {
  const std::string state_text = read_text(dir / "state.vtp");
  record["state_bytes"] = state_text.size();
  record["state_hash"] = stable_hash(state_text);
  write_atomic(dir / record_name, record.dump(2) + "\n");
  std::error_code ec;
  fs::remove(dir / "checkpoint.bin", ec);
  fs::remove(dir / "checkpoint.hash", ec);
  return record;
}

bool record_finished(const fs::path &dir, const std::string &record_name, const std::string &hash) {
  std::error_code ec;
  if (!fs::exists(dir / record_name, ec) || !fs::exists(dir / "state.vtp", ec)) return false;
  try {
    const auto j = nlohmann::json::parse(read_text(dir / record_name));
    if (j.value("hash", "") != hash || j.value("status", "") != "done") return false;
    if (!j.contains("state_bytes")) return true;  // written before the state was fingerprinted
    if (fs::file_size(dir / "state.vtp", ec) != j["state_bytes"].get<std::uintmax_t>() || ec) return false;
    return stable_hash(read_text(dir / "state.vtp")) == j.value("state_hash", "");
  } catch (...) {
    return false;
  }
}

nlohmann::json substrate_record(const engine::ParticleSet &substrate) {
  double level = 0, rq = 0;  // from the spheres at hand: generating the substrate again would cost as much
  for (std::size_t i = 0; i < substrate.size(); ++i) level += substrate.z[i] + substrate.radius[i];
  level /= double(substrate.size());
  for (std::size_t i = 0; i < substrate.size(); ++i) rq += std::pow(substrate.z[i] + substrate.radius[i] - level, 2);
  return {{"spheres", substrate.size()},
          {"sphere_diameter", 2 * substrate.radius.front()},
          {"mean_plane", level},
          {"rq", std::sqrt(rq / double(substrate.size()))}};
}

std::string case_hash(const Scene &scene) {
  nlohmann::json s = to_json(scene);
  s["time"].erase("checkpoint_interval");
  s.erase("threads");
  s.erase("backend");
  return stable_hash(s.dump());
}

bool case_finished(const fs::path &dir, const std::string &hash) { return record_finished(dir, "case.json", hash); }

}  // namespace spreadmap
