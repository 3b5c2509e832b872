#include "workflow/cases/heap_cache.hpp"

#include <spdlog/spdlog.h>

#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>

#include "core/files.hpp"
#include "engine/vtp_io.hpp"
#include "workflow/spreading/case_setup.hpp"

namespace spreadmap {
namespace {

std::mutex heap_mutex;
std::map<std::string, std::shared_ptr<std::mutex>> heap_locks;

// The lock of one heap, made at its first use: cases of other heaps settle in parallel.
std::shared_ptr<std::mutex> lock_of_heap(const std::string &key) {
  std::lock_guard<std::mutex> g(heap_mutex);
  auto &l = heap_locks[key];
  if (!l) l = std::make_shared<std::mutex>();
  return l;
}

}  // namespace

template <class Real>
engine::ParticleSet settled_heap(const Scene &scene, PluginRegistry &reg, const CaseRequest &req) {
  const std::string key = heap_hash(scene, reg);
  const std::shared_ptr<std::mutex> lock = lock_of_heap(key);
  std::lock_guard<std::mutex> g(*lock);  // one case settles; the others wait and reuse it
  const fs::path file = req.heaps / ("heap_" + key + ".vtp");
  // The heap is sealed by the hash of its file (heap_<key>.hash, written after it): a heap changed or
  // damaged since is settled again, never reused, so no case starts from a heap that no longer is.
  const fs::path seal = req.heaps / ("heap_" + key + ".hash");
  if (fs::exists(file)) {
    const std::string text = read_text(file);
    if (fs::exists(seal) && read_text(seal) == stable_hash(text)) {
      spdlog::debug("{}: reusing settled heap {}", req.id, file.string());
      return engine::read_vtp(file).particles;
    }
    spdlog::warn("{}: the settled heap {} {}; settling it again", req.id, file.string(),
                 fs::exists(seal) ? "changed since it was written (its hash does not match)" : "has no hash beside it");
  }
  engine::ParticleSet heap = settle_heap<Real>(scene, reg, req.id, req.dir / "scene.json", [&req](double f) {
    if (req.progress) req.progress(0.1 * f, "settling");
  });
  engine::write_vtp(file, heap, 0.0);
  write_atomic(seal, stable_hash(read_text(file)));
  return heap;
}

std::string heap_hash(const Scene &scene, PluginRegistry &registry) {
  const nlohmann::json all = to_json(scene);
  nlohmann::json s = {{"powder", all["powder"]},   {"domain", all["domain"]},
                      {"contact", all["contact"]}, {"substrate", all["substrate"]},
                      {"gravity", all["gravity"]}, {"precision", all["precision"]},
                      {"time", all["time"]}};
  s["substrate"].erase("roughness");  // the heap settles on the plate and is fed onto a substrate of spheres after
  s["substrate"].erase("height_map");
  for (const char *k : {"relax", "checkpoint_interval", "snapshots"}) s["time"].erase(k);
  // The spreader as the heap sees it: its law and its body at rest, as it describes itself (its
  // motion, e.g. a speed or a rotation, does not change the heap).
  nlohmann::json body = to_json(describe_spreader(scene, registry, "scene.json"));
  for (const char *k : {"end", "speed", "duration"}) body.erase(k);
  s["spreader"] = {{"use", scene.spreader.use}, {"law", scene.spreader.law}, {"at_rest", body}};
  if (all.contains("machine")) s["machine"] = all["machine"];  // the reservoir it fills
  return stable_hash(s.dump());
}

template engine::ParticleSet settled_heap<double>(const Scene &, PluginRegistry &, const CaseRequest &);
template engine::ParticleSet settled_heap<float>(const Scene &, PluginRegistry &, const CaseRequest &);

}  // namespace spreadmap
