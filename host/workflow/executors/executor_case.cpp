// One case run on behalf of an executor, its messages, and its manifest entry.
#include <spdlog/spdlog.h>
#include <unistd.h>

#include <chrono>
#include <mutex>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "cuda/backend.hpp"
#include "workflow/executors/executor_hook.hpp"
#include "core/files.hpp"
#include "workflow/figures/figure_style.hpp"
#include "workflow/figures/stage_figures.hpp"
#include "workflow/characterise/layer_eval.hpp"
#include "workflow/run/run_dir.hpp"

namespace spreadmap {
namespace {

std::string host_name() {
  char buf[256] = {};
  if (::gethostname(buf, sizeof buf - 1) != 0) return "?";
  return buf;
}

// The end state as a picture: cases/cNNN/snapshot.png, with the spreader where it stopped, and with
// `render: {frames: true}` the frames of the snapshot series (case.json lists its files and the
// spreader's pose at each). A figure never fails a case.
void draw_snapshot(const CaseRequest &req, const nlohmann::json &c) {
  try {
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

}  // namespace

void redraw_missing_snapshot(const CaseRequest &req) {
  if (!figures::available() || figures::whole_png(req.dir / "snapshot.png")) return;
  try {
    spdlog::info("{}: snapshot.png is missing or torn; drawing it again", req.id);
    draw_snapshot(req, nlohmann::json::parse(read_text(req.dir / "case.json")));
  } catch (const std::exception &e) {
    spdlog::warn("{}: snapshot not drawn: {}", req.id, e.what());
  }
}

namespace {

// Which backend this process's cases run on, said once by each process that runs cases (every MPI
// rank and Slurm task for itself). The stage has already refused a backend that cannot be honoured.
void say_backend_once(const Scene &scene) {
  static std::once_flag said;
  std::call_once(said, [&] {
    std::string note;
    try {
      cuda::choose_backend(scene.backend, note);
    } catch (const std::exception &) {
      return;  // the case's own set-up reports it
    }
    spdlog::info("{}", note);
  });
}

}  // namespace

nlohmann::json job_to_json(const CaseJob &job) {
  const CaseRequest &r = job.request;
  return {{"index", job.index},        {"render", job.render}, {"id", r.id},
          {"scene", to_json(r.scene)}, {"inputs", r.inputs},   {"dir", r.dir.string()},
          {"heaps", r.heaps.string()}, {"threads", r.threads}};
}

CaseJob job_from_json(const nlohmann::json &j) {
  CaseJob job;
  job.index = j.at("index").get<std::size_t>();
  job.render = j.at("render").get<bool>();
  job.request.id = j.at("id").get<std::string>();
  job.request.scene = scene_from_json(j.at("scene"), "the case job's scene");
  job.request.inputs = j.at("inputs");
  job.request.dir = j.at("dir").get<std::string>();
  job.request.heaps = j.at("heaps").get<std::string>();
  job.request.threads = j.at("threads").get<int>();
  return job;
}

nlohmann::json outcome_to_json(const CaseOutcome &o) {
  return {{"index", o.index},         {"id", o.id},       {"ok", o.ok},
          {"exit_code", o.exit_code}, {"error", o.error}, {"result", o.result},
          {"start", o.start},         {"end", o.end},     {"wall_seconds", o.wall_seconds},
          {"rank", o.rank},           {"host", o.host}};
}

CaseOutcome outcome_from_json(const nlohmann::json &j) {
  CaseOutcome o;
  o.index = j.at("index").get<std::size_t>();
  o.id = j.at("id").get<std::string>();
  o.ok = j.at("ok").get<bool>();
  o.exit_code = j.at("exit_code").get<int>();
  o.error = j.at("error").get<std::string>();
  o.result = j.at("result");
  o.start = j.at("start").get<std::string>();
  o.end = j.at("end").get<std::string>();
  o.wall_seconds = j.at("wall_seconds").get<double>();
  o.rank = j.at("rank").get<int>();
  o.host = j.at("host").get<std::string>();
  return o;
}

CaseOutcome run_case_job(const CaseJob &job, PluginRegistry &registry) {
  CaseOutcome o;
  o.index = job.index;
  o.id = job.request.id;
  o.host = host_name();
  o.start = RunDirectory::now_iso();
  const auto t0 = std::chrono::steady_clock::now();
  try {
    say_backend_once(job.request.scene);
    o.result = run_case(job.request, registry);
    o.ok = true;
  } catch (const std::exception &e) {
    set_failure(o, e);
  }
  o.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  o.end = RunDirectory::now_iso();
  // The timing beside the case, before the figure: a kill between the two leaves it for the manifest
  // (simulate_stage.cpp takes it from here when the manifest never heard of the outcome).
  if (o.ok)
    write_atomic(job.request.dir / "timing.json",
                 nlohmann::json({{"start", o.start}, {"end", o.end}, {"wall_seconds", o.wall_seconds}, {"host", o.host}})
                         .dump(2) +
                     "\n");
  if (o.ok && job.render) draw_snapshot(job.request, o.result);
  return o;
}

void set_failure(CaseOutcome &o, const std::exception &e) {
  o.ok = false;
  o.error = e.what();
  const auto *error = dynamic_cast<const Error *>(&e);
  o.exit_code = error ? error->exit_code : exit_failure;
}

void log_done(const CaseOutcome &o, const std::string &where) {
  spdlog::info("{} done{}: {} steps, {:.1f} s, {:.3g} particle-steps/s, {} removed", o.id, where,
               o.result.value("steps", 0.0), o.wall_seconds, o.result.value("particle_steps_per_second", 0.0),
               o.result.value("removed", 0.0));
}

void log_failure(const CaseOutcome &o, const std::string &where) {
  if (o.exit_code == exit_interrupted) spdlog::info("{}{}: {}", o.id, where, o.error);
  else spdlog::error("{}{}: {}", o.id, where, o.error);
}

void record_outcome(RunDirectory &run, const CaseOutcome &outcome) {
  if (!outcome.ok) return;
  run.update_manifest([&](nlohmann::json &m) {
    for (auto &c : m["cases"])
      if (c["id"] == outcome.id) {
        c["start"] = outcome.start;
        c["end"] = outcome.end;
        c["wall_seconds"] = outcome.wall_seconds;
        c["status"] = "done";
        c["rank"] = outcome.rank;
        c["host"] = outcome.host;
      }
  });
}

void throw_outcome(const CaseOutcome &outcome, const std::string &where) {
  const std::string message = where.empty() ? outcome.error : outcome.id + where + ": " + outcome.error;
  if (outcome.exit_code == exit_interrupted) throw Interrupted(message);
  if (outcome.exit_code == exit_input) throw InputError(message);
  if (outcome.exit_code == exit_plugin) throw PluginError(message);
  throw RunFailure(message);
}

}  // namespace spreadmap
