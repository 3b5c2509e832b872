#include "workflow/verify/verify_runs.hpp"

#include "workflow/run/run_dir.hpp"

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/files.hpp"
#include "core/stop.hpp"
#include "workflow/executors/executor_hook.hpp"
#include "workflow/executors/local_executor.hpp"
#include "workflow/cases/case_runner.hpp"
#include "workflow/spreading/coarse_grain.hpp"
#include "workflow/cases/replicates.hpp"

namespace spreadmap {

Scene verify_run_scene(const VerifyPoint &point, std::size_t first_seed, std::size_t r) {
  return replicate_scene(point.scene, max_replicates + first_seed + r);
}

std::vector<std::vector<nlohmann::json>> run_and_measure(StageContext &ctx, const std::vector<VerifyPoint> &points,
                                                         std::size_t runs, std::size_t first_seed,
                                                         const CharacteriseSettings &settings) {
  std::vector<std::vector<CaseRequest>> requests(points.size());
  CaseBatch batch{{}, points.size() * runs, "verify"};
  for (std::size_t p = 0; p < points.size(); ++p)
    for (std::size_t r = 0; r < runs; ++r) {
      CaseRequest req;
      req.id = replicate_id(points[p].id, r);
      req.scene = verify_run_scene(points[p], first_seed, r);
      req.inputs = points[p].inputs;
      req.dir = ctx.run.root() / "verify" / req.id;
      req.heaps = ctx.run.heaps();
      requests[p].push_back(req);
      if (!ctx.options.force && case_finished(req.dir, case_hash(req.scene))) continue;
      if (ctx.options.force) {
        std::error_code ec;
        fs::remove(req.dir / "checkpoint.bin", ec);
      }
      fs::create_directories(req.dir);
      write_scene_file(req.dir / "scene.json", coarse_grained(req.scene, ctx.registry));  // as the engine runs it
      batch.jobs.push_back({p * runs + r, req, false});
    }
  spdlog::info("verify: {} points x {} runs, {} to run, {} finished already", points.size(), runs, batch.jobs.size(),
               batch.total - batch.jobs.size());
  if (!batch.jobs.empty()) LocalExecutor(ctx.options.jobs, ctx.options.case_threads).run_cases(batch, ctx);
  if (stop_requested()) throw Interrupted("interrupted: finished runs are kept; run the same command again to resume");

  const std::string settings_key = settings_hash(settings);
  std::vector<std::vector<nlohmann::json>> metrics(points.size());
  for (std::size_t p = 0; p < points.size(); ++p)
    for (const auto &req : requests[p]) {
      bool evaluated = false;
      const std::string key = stable_hash(settings_key + case_hash(req.scene));
      metrics[p].push_back(
          case_metrics(ctx.registry, settings, req.dir, "verify/" + req.id, key, ctx.options.force, evaluated));
    }
  return metrics;
}

}  // namespace spreadmap
