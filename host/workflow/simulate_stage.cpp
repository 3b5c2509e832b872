// simulate: runs every case of the design (one after another, or --jobs N at once), each
// resumable; a finished case whose inputs did not change is never recomputed.
#include <spdlog/spdlog.h>

#include <atomic>
#include <mutex>
#include <thread>

#include "core/error.hpp"
#include "cuda/backend.hpp"
#include "core/files.hpp"
#include "core/schema.hpp"
#include "core/stop.hpp"
#include "workflow/adaptive_run.hpp"
#include "workflow/case_runner.hpp"
#include "workflow/coarse_grain.hpp"
#include "workflow/design.hpp"
#include "workflow/executor_hook.hpp"
#include "workflow/figure_style.hpp"
#include "workflow/figures.hpp"
#include "workflow/layer_eval.hpp"
#include "workflow/progress.hpp"
#include "workflow/stage.hpp"

namespace spreadmap {
namespace {

class SimulateStage : public Stage {
 public:
  void validate(const Workflow &wf, const StageEntry &entry, const nlohmann::json &scene, PluginRegistry &registry,
                Diagnostics &diag) override {
    const std::string file = wf.file.string();
    for (const auto &kv : entry.config) {
      const std::string key = kv.first.as<std::string>();
      if (key == "render") {
        style_ = figures::read_style(kv.second, true, true, file, "simulate.render", diag);
        render_ = style_.on;
      }
      if (key != "design" && key != "render")
        diag.error(Location::of(file, kv.first), "simulate." + key, "unknown key", "known: design, render");
    }
    if (scene.is_null() || !scene.contains("spreader")) return;  // scene errors already reported
    design_ = parse_design(entry.config["design"], file, "simulate.design", scene, registry, diag);
  }

  void run(StageContext &ctx) override {
    figures::use_style(style_);
    if (design_.type == "adaptive") return run_adaptive_design(ctx, design_, render_);
    const std::size_t n = design_.cases.size();
    const auto &only_case = ctx.options.only_case;
    if (only_case && *only_case >= n)
      throw InputError("error: --case " + std::to_string(*only_case) + ": the design has " + std::to_string(n) +
                       " cases, numbered 0 to " + std::to_string(n - 1));
    std::vector<CaseRequest> todo;
    std::vector<std::size_t> todo_index;  // design position of each todo entry, for an executor
    nlohmann::json cases = nlohmann::json::array();
    for (std::size_t i = 0; i < n; ++i) {
      if (only_case && i != *only_case) continue;
      CaseRequest req;
      req.id = RunDirectory::case_id(i);
      req.scene = case_scene(ctx.scene, design_, i);
      req.inputs = case_inputs(design_, i);
      req.dir = ctx.run.case_dir(req.id);
      req.heaps = ctx.run.heaps();
      const std::string hash = case_hash(req.scene);
      cases.push_back({{"id", req.id}, {"inputs", req.inputs}, {"hash", hash}});
      if (!ctx.options.force && case_finished(req.dir, hash)) continue;
      if (ctx.options.force) {
        std::error_code ec;
        fs::remove(req.dir / "checkpoint.bin", ec);
      }
      write_atomic(req.dir / "scene.json", coarse_grained(req.scene, ctx.registry).dump(2) + "\n");  // as the engine runs it
      todo.push_back(std::move(req));
      todo_index.push_back(i);
    }
    if (ctx.options.records_manifest()) ctx.run.update_manifest([&](nlohmann::json &m) {
      nlohmann::json old = m.value("cases", nlohmann::json::array());
      for (auto &c : cases)
        for (const auto &o : old)
          if (o.value("id", "") == c["id"] && o.value("hash", "") == c["hash"])
            for (const char *k : {"start", "end", "wall_seconds", "status"})
              if (o.contains(k)) c[k] = o[k];
      // Finished where no record says so: by a Slurm array task (they leave the manifest alone), or
      // on an MPI rank killed before rank 0 heard of it. case.json is the proof.
      for (auto &c : cases)
        if (!c.contains("status") && case_finished(ctx.run.case_dir(c["id"].get<std::string>()), c["hash"].get<std::string>()))
          c["status"] = "done";
      m["cases"] = cases;
      m["design"] = {{"type", design_.type}, {"variables", [&] {
                        auto v = nlohmann::json::array();
                        for (const auto &d : design_.variables) v.push_back({{"name", d.key.name}, {"unit", d.key.param->unit}});
                        return v;
                      }()}};
      m["plugins"]["contact/" + ctx.scene["contact"]["use"].get<std::string>()] =
          ctx.registry.get("contact", ctx.scene["contact"]["use"]).descriptor->version;
      m["plugins"]["spreader/" + ctx.scene["spreader"]["use"].get<std::string>()] =
          ctx.registry.get("spreader", ctx.scene["spreader"]["use"]).descriptor->version;
    });
    if (only_case)
      spdlog::info("simulate: case {} of {}: {}", RunDirectory::case_id(*only_case), n,
                   todo.empty() ? "finished already" : "to run");
    else
      spdlog::info("simulate: {} cases, {} to run, {} finished already", n, todo.size(), n - todo.size());
    std::string backend_note;  // throws InputError for `cuda` with no usable device
    const cuda::Backend backend = cuda::choose_backend(ctx.scene["backend"].get<std::string>(), backend_note);
    (void)backend;  // each case attaches the backend itself (case_setup.cpp: attach_backend)
    if (only_case || ctx.options.executor) {  // the cases run one by one here, on MPI ranks or as Slurm tasks
      CaseBatch batch{{}, n};
      for (std::size_t k = 0; k < todo.size(); ++k) batch.jobs.push_back({todo_index[k], std::move(todo[k]), render_});
      if (only_case) {
        for (auto &job : batch.jobs) run_job_here(job, ctx.registry, ctx.options.case_threads);
      } else {
        ctx.options.executor->run_cases(batch, ctx);
      }
      return;
    }
    if (todo.empty()) return;
    static std::once_flag backend_said;
    std::call_once(backend_said, [&] { spdlog::info("{}", backend_note); });

    Progress progress("simulate", todo.size(), ctx.options.quiet);
    const int jobs = std::max(1, std::min<int>(ctx.options.jobs, int(todo.size())));
    const int cores = std::max(1u, std::thread::hardware_concurrency());
    const int threads_requested = ctx.scene["threads"].get<int>();
    std::atomic<std::size_t> next{0};
    std::mutex error_mutex;
    std::exception_ptr first_error;
    auto worker = [&] {
      for (;;) {
        const std::size_t k = next++;
        if (k >= todo.size() || stop_requested()) return;
        {
          std::lock_guard<std::mutex> g(error_mutex);
          if (first_error) return;
        }
        CaseRequest &req = todo[k];
        req.threads = threads_requested > 0 ? threads_requested : std::max(1, cores / jobs);
        req.progress = [&progress, k, id = req.id](double f, const std::string &d) { progress.update(k, f, id + " " + d); };
        const std::string start = RunDirectory::now_iso();
        const auto t0 = std::chrono::steady_clock::now();
        try {
          const auto result = run_case(req, ctx.registry);
          const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          ctx.run.update_manifest([&](nlohmann::json &m) {
            for (auto &c : m["cases"])
              if (c["id"] == req.id) {
                c["start"] = start;
                c["end"] = RunDirectory::now_iso();
                c["wall_seconds"] = wall;
                c["status"] = "done";
              }
          });
          progress.done_item();
          if (render_) snapshot(req);
          spdlog::info("{} done: {} steps, {:.1f} s, {:.3g} particle-steps/s, {} removed", req.id,
                       result["steps"].get<double>(), wall, result["particle_steps_per_second"].get<double>(),
                       result["removed"].get<double>());
        } catch (...) {
          std::lock_guard<std::mutex> g(error_mutex);
          if (!first_error) first_error = std::current_exception();
        }
      }
    };
    std::vector<std::thread> pool;
    for (int j = 1; j < jobs; ++j) pool.emplace_back(worker);
    worker();
    for (auto &t : pool) t.join();
    progress.finish();
    if (first_error) std::rethrow_exception(first_error);
    if (stop_requested())
      throw Interrupted("interrupted: finished cases are kept; run the same command again to resume");
  }

 private:
  // The end state as a picture: cases/cNNN/snapshot.png.
  // The final state with the spreader where it stopped, and with `render: {frames: true}` the frames of
  // the snapshot series (case.json lists its files and the spreader's pose at each).
  static void snapshot(const CaseRequest &req) {
    try {
      const auto c = nlohmann::json::parse(read_text(req.dir / "case.json"));
      const std::string title = figures::case_title(req.id, req.inputs);
      figures::snapshot(read_particle_file(req.dir / "state.vtp"), req.scene, c, req.dir / "snapshot.png", title);
      if (!figures::current_style().frames || !c.contains("series")) return;
      std::vector<engine::ParticleSet> states;
      std::vector<nlohmann::json> poses;
      for (const auto &e : c["series"]) {
        states.push_back(read_particle_file(req.dir / e["file"].get<std::string>()));
        poses.push_back(e["spreader"]);
      }
      const auto n = figures::frames(states, poses, req.scene, c, req.dir / "frames", title);
      spdlog::info("{}: {} frames in {}", req.id, n, (req.dir / "frames").string());
    } catch (const std::exception &e) {
      spdlog::warn("{}: snapshot not drawn: {}", req.id, e.what());
    }
  }
  Design design_;
  figures::Style style_;
  bool render_ = true;
};

}  // namespace

std::unique_ptr<Stage> make_simulate_stage() { return std::make_unique<SimulateStage>(); }

}  // namespace spreadmap
