// Simulation::save_checkpoint / load_checkpoint. The state is stored exactly as it is in memory
// (current order, the list with its history and reference positions, forces of the last
// evaluation), so that a resumed run continues bitwise identically.
#include <core/files.hpp>
#include <engine/binary_io.hpp>
#include <engine/simulation.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>

namespace spreadmap::engine {

namespace {
constexpr char magic[16] = "spreadmap-ckpt";
constexpr std::uint32_t format_version = 2;  // 2: sleeping (mobile, calm, the sleep region)
}  // namespace

template <class Real> void Simulation<Real>::save_checkpoint(const std::filesystem::path &path) const {
  sync_host();
  BinaryWriter w;
  for (char c : magic) w.value(c);
  w.value(format_version);
  w.value<std::uint32_t>(sizeof(Real));
  w.value<std::uint64_t>(p_.size());
  w.value<std::uint32_t>(static_cast<std::uint32_t>(planes_.size()));
  w.value<std::uint32_t>(static_cast<std::uint32_t>(geometries_.size()));
  w.value<std::uint32_t>(pair_law_.ops->history);
  for (const auto &pl : planes_) w.value<std::uint32_t>(pl.slot.history);
  for (const auto &ge : geometries_) w.value<std::uint32_t>(ge.slot.history);

  w.value(time_);
  w.value(step_);
  w.value(dt_);
  w.value(skin_);
  w.value(speed_limit_);
  w.value<std::uint8_t>(rotate_);
  w.value<std::uint8_t>(step_resolved_);
  w.value<std::uint8_t>(list_valid_);
  w.value<std::uint8_t>(forces_valid_);
  w.value(next_id_);
  w.value(counters_.removed);
  w.value(counters_.list_builds);
  w.value(sleep_x_max_);
  w.value<std::uint64_t>(asleep_at_build_);

  auto &p = const_cast<ParticleArrays<Real> &>(p_);
  p.for_each_real([&](std::vector<Real> &c) { w.array(c); });
  p.for_each_index([&](std::vector<std::uint32_t> &c) { w.array(c); });
  w.array(list_.start);
  w.array(list_.nbr);
  w.array(list_.hist);
  for (const auto &pl : planes_) {
    w.value(pl.wall.point);
    w.value(pl.wall.velocity);
    w.value<std::uint8_t>(pl.wall.active);
    w.value<std::uint8_t>(pl.slot.touched);
    w.array(pl.slot.hist);
  }
  for (const auto &ge : geometries_) {
    w.value<std::uint8_t>(ge.slot.touched);
    w.array(ge.slot.hist);
  }
  write_atomic(path, w.bytes());
}

template <class Real> void Simulation<Real>::load_checkpoint(const std::filesystem::path &path) {
  host_changes();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SetupError(fmt::format("{}: cannot open the checkpoint for reading", path.string()));
  std::ostringstream all;
  all << in.rdbuf();
  BinaryReader r(all.str(), path.string());
  for (char c : magic)
    if (r.value<char>() != c) r.fail("wrong magic bytes");
  if (r.value<std::uint32_t>() != format_version) r.fail("unknown format version");
  const auto real_size = r.value<std::uint32_t>();
  if (real_size != sizeof(Real))
    throw SetupError(fmt::format("{}: the checkpoint was written in {} precision, this run uses {}; resume with the "
                                 "same precision",
                                 path.string(), real_size == 4 ? "float" : "double",
                                 sizeof(Real) == 4 ? "float" : "double"));
  const auto n = r.value<std::uint64_t>();
  const auto n_planes = r.value<std::uint32_t>(), n_geometries = r.value<std::uint32_t>();
  if (n_planes != planes_.size() || n_geometries != geometries_.size())
    throw SetupError(fmt::format("{}: the checkpoint has {} plane walls and {} geometries, this scene has {} and {}; "
                                 "add the same walls and geometries before loading",
                                 path.string(), n_planes, n_geometries, planes_.size(), geometries_.size()));
  auto check_history = [&](std::uint32_t expected, const std::string &what) {
    const auto h = r.value<std::uint32_t>();
    if (h != expected)
      throw SetupError(fmt::format("{}: {} keeps {} history values per contact in the checkpoint but {} in this "
                                   "scene; resume with the same contact laws",
                                   path.string(), what, h, expected));
  };
  check_history(pair_law_.ops->history, "the particle-particle law");
  for (const auto &pl : planes_) check_history(pl.slot.history, "plane wall '" + pl.wall.name + "'");
  for (const auto &ge : geometries_) check_history(ge.slot.history, "geometry '" + ge.geometry.name + "'");

  time_ = r.value<double>();
  step_ = r.value<std::uint64_t>();
  dt_ = r.value<double>();
  skin_ = r.value<double>();
  speed_limit_ = r.value<double>();
  rotate_ = r.value<std::uint8_t>() != 0;
  step_resolved_ = r.value<std::uint8_t>() != 0;
  list_valid_ = r.value<std::uint8_t>() != 0;
  forces_valid_ = r.value<std::uint8_t>() != 0;
  next_id_ = r.value<std::uint32_t>();
  counters_ = RunCounters{};
  counters_.removed = r.value<std::uint64_t>();
  counters_.list_builds = r.value<std::uint64_t>();
  sleep_x_max_ = r.value<double>();
  asleep_at_build_ = r.value<std::uint64_t>();

  p_.for_each_real([&](std::vector<Real> &c) {
    r.array(c);
    if (c.size() != n) r.fail("a particle column of the wrong length");
  });
  p_.for_each_index([&](std::vector<std::uint32_t> &c) {
    r.array(c);
    if (c.size() != n) r.fail("a particle column of the wrong length");
  });
  r.array(list_.start);
  r.array(list_.nbr);
  r.array(list_.hist);
  if (list_.start.size() != n + 1 || list_.start.back() != list_.nbr.size() ||
      list_.hist.size() != list_.nbr.size() * pair_law_.ops->history)
    r.fail("an inconsistent neighbour list");
  list_.restore_mirror(settings_.pairs_once, pair_law_.ops->history);
  asleep_ = std::size_t(std::count(p_.mobile.begin(), p_.mobile.end(), Real(0)));
  if (settings_.sleep) find_border();
  for (auto &ge : geometries_) ge.near_valid = false;  // searched again at the next evaluation
  forces_zeroed_ = false;
  for (auto &pl : planes_) {
    pl.wall.point = r.value<std::array<double, 3>>();
    pl.wall.velocity = r.value<std::array<double, 3>>();
    pl.wall.active = r.value<std::uint8_t>() != 0;
    pl.slot.touched = r.value<std::uint8_t>() != 0;
    r.array(pl.slot.hist);
    if (pl.slot.hist.size() != n * pl.slot.history) r.fail("a wall history of the wrong length");
  }
  for (auto &ge : geometries_) {
    ge.slot.touched = r.value<std::uint8_t>() != 0;
    r.array(ge.slot.hist);
    if (ge.slot.hist.size() != n * ge.slot.history) r.fail("a geometry history of the wrong length");
  }
  if (!r.at_end()) r.fail("trailing bytes");
  resize_walls();
}

template void Simulation<double>::save_checkpoint(const std::filesystem::path &) const;
template void Simulation<float>::save_checkpoint(const std::filesystem::path &) const;
template void Simulation<double>::load_checkpoint(const std::filesystem::path &);
template void Simulation<float>::load_checkpoint(const std::filesystem::path &);

}  // namespace spreadmap::engine
