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
// 2: sleeping (mobile, calm, the sleep region); 3: checksum; 4: the sleep region's depth bound
constexpr std::uint32_t format_version = 4;
}  // namespace

template <class Real> void Simulation<Real>::save_checkpoint(const std::filesystem::path &path) const {
  sync_host();
  BinaryWriter w;
  for (char c : magic) w.value(c);
  w.value(format_version);
  w.value<std::uint32_t>(sizeof(Real));
  w.value<std::uint64_t>(state_.particles.size());
  w.value<std::uint32_t>(static_cast<std::uint32_t>(state_.planes.size()));
  w.value<std::uint32_t>(static_cast<std::uint32_t>(state_.geometries.size()));
  w.value<std::uint32_t>(law_history(state_.pair_law));
  for (const auto &pl : state_.planes) w.value<std::uint32_t>(pl.slot.history);
  for (const auto &ge : state_.geometries) w.value<std::uint32_t>(ge.slot.history);

  w.value(state_.time);
  w.value(state_.step);
  w.value(state_.dt);
  w.value(state_.skin);
  w.value(state_.speed_limit);
  w.value<std::uint8_t>(state_.rotate);
  w.value<std::uint8_t>(step_resolved_);
  w.value<std::uint8_t>(state_.list_valid);
  w.value<std::uint8_t>(state_.forces_valid);
  w.value(next_id_);
  w.value(state_.counters.removed);
  w.value(state_.counters.list_builds);
  w.value(sleep_x_max_);
  w.value(sleep_z_max_);
  w.value<std::uint64_t>(asleep_at_build_);

  auto &p = const_cast<ParticleArrays<Real> &>(state_.particles);
  p.for_each_real([&](std::vector<Real> &c) { w.array(c); });
  p.for_each_index([&](std::vector<std::uint32_t> &c) { w.array(c); });
  w.array(state_.list.start);
  w.array(state_.list.nbr);
  w.array(state_.list.hist);
  for (const auto &pl : state_.planes) {
    w.value(pl.wall.point);
    w.value(pl.wall.velocity);
    w.value<std::uint8_t>(pl.wall.active);
    w.value<std::uint8_t>(pl.slot.touched);
    w.array(pl.slot.hist);
  }
  for (const auto &ge : state_.geometries) {
    w.value<std::uint8_t>(ge.slot.touched);
    w.array(ge.slot.hist);
  }
  write_atomic(path, w.sealed());
}

template <class Real> void Simulation<Real>::load_checkpoint(const std::filesystem::path &path) {
  host_changes();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SetupError(fmt::format("{}: cannot open the checkpoint for reading", path.string()));
  std::ostringstream all;
  all << in.rdbuf();
  std::string bytes = all.str();
  {  // magic and version first, unsealed: a foreign or older file is named so, not called damaged
    BinaryReader head(bytes.substr(0, sizeof magic + sizeof format_version), path.string());
    for (char c : magic)
      if (head.value<char>() != c) head.fail("wrong magic bytes");
    if (head.value<std::uint32_t>() != format_version) head.fail("unknown format version");
  }
  BinaryReader r = BinaryReader::sealed(std::move(bytes), path.string());
  for (char c : magic)
    if (r.value<char>() != c) r.fail("wrong magic bytes");
  if (r.value<std::uint32_t>() != format_version) r.fail("unknown format version");
  const auto real_size = r.value<std::uint32_t>();
  if (real_size != sizeof(Real))
    throw SetupError(
        fmt::format("{}: the checkpoint was written in {} precision, this run uses {}; resume with the "
                    "same precision",
                    path.string(), real_size == 4 ? "float" : "double", sizeof(Real) == 4 ? "float" : "double"));
  const auto n = r.value<std::uint64_t>();
  const auto n_planes = r.value<std::uint32_t>(), n_geometries = r.value<std::uint32_t>();
  if (n_planes != state_.planes.size() || n_geometries != state_.geometries.size())
    throw SetupError(
        fmt::format("{}: the checkpoint has {} plane walls and {} geometries, this scene has {} and {}; "
                    "add the same walls and geometries before loading",
                    path.string(), n_planes, n_geometries, state_.planes.size(), state_.geometries.size()));
  auto check_history = [&](std::uint32_t expected, const std::string &what) {
    const auto h = r.value<std::uint32_t>();
    if (h != expected)
      throw SetupError(
          fmt::format("{}: {} keeps {} history values per contact in the checkpoint but {} in this "
                      "scene; resume with the same contact laws",
                      path.string(), what, h, expected));
  };
  check_history(law_history(state_.pair_law), "the particle-particle law");
  for (const auto &pl : state_.planes) check_history(pl.slot.history, "plane wall '" + pl.wall.name + "'");
  for (const auto &ge : state_.geometries) check_history(ge.slot.history, "geometry '" + ge.geometry.name + "'");

  state_.time = r.value<double>();
  state_.step = r.value<std::uint64_t>();
  state_.dt = r.value<double>();
  state_.skin = r.value<double>();
  state_.speed_limit = r.value<double>();
  state_.rotate = r.value<std::uint8_t>() != 0;
  step_resolved_ = r.value<std::uint8_t>() != 0;
  state_.list_valid = r.value<std::uint8_t>() != 0;
  state_.forces_valid = r.value<std::uint8_t>() != 0;
  state_.leaving = true;  // not stored: whether any particle is outside is found at the next build
  next_id_ = r.value<std::uint32_t>();
  state_.counters = RunCounters{};
  state_.counters.removed = r.value<std::uint64_t>();
  state_.counters.list_builds = r.value<std::uint64_t>();
  sleep_x_max_ = r.value<double>();
  sleep_z_max_ = r.value<double>();
  asleep_at_build_ = r.value<std::uint64_t>();

  auto &p = state_.particles;
  p.for_each_real([&](std::vector<Real> &c) {
    r.array(c);
    if (c.size() != n) r.fail("a particle column of the wrong length");
  });
  p.for_each_index([&](std::vector<std::uint32_t> &c) {
    r.array(c);
    if (c.size() != n) r.fail("a particle column of the wrong length");
  });
  r.array(state_.list.start);
  r.array(state_.list.nbr);
  r.array(state_.list.hist);
  if (state_.list.start.size() != n + 1 || state_.list.start.back() != state_.list.nbr.size() ||
      state_.list.hist.size() != state_.list.nbr.size() * law_history(state_.pair_law))
    r.fail("an inconsistent neighbour list");
  // every index is checked before a loop trusts it: a neighbour beyond the particles is a crash
  for (std::size_t i = 0; i < n; ++i)
    if (state_.list.start[i] > state_.list.start[i + 1]) r.fail("a neighbour list whose rows run backwards");
  for (const auto j : state_.list.nbr)
    if (j >= n) r.fail(fmt::format("a neighbour index {} beyond the {} particles", j, n));
  for (const auto j : p.list_index)
    if (j != no_index && j >= n) r.fail(fmt::format("a list index {} beyond the {} particles", j, n));
  state_.list.restore_mirror(state_.pairs_once());
  fixed_ = std::size_t(std::count(p.inv_m.begin(), p.inv_m.end(), Real(0)));
  asleep_ = std::size_t(std::count(p.mobile.begin(), p.mobile.end(), Real(0))) - fixed_;
  if (state_.settings.sleep) find_border();
  for (auto &ge : state_.geometries) ge.near_valid = false;  // searched again at the next evaluation
  forces_zeroed_ = false;
  for (auto &pl : state_.planes) {
    pl.wall.point = r.value<std::array<double, 3>>();
    pl.wall.velocity = r.value<std::array<double, 3>>();
    pl.wall.active = r.value<std::uint8_t>() != 0;
    pl.slot.touched = r.value<std::uint8_t>() != 0;
    r.array(pl.slot.hist);
    if (pl.slot.hist.size() != n * pl.slot.history) r.fail("a wall history of the wrong length");
  }
  for (auto &ge : state_.geometries) {
    ge.slot.touched = r.value<std::uint8_t>() != 0;
    r.array(ge.slot.hist);
    if (ge.slot.hist.size() != n * ge.slot.history) r.fail("a geometry history of the wrong length");
  }
  if (!r.at_end()) r.fail("trailing bytes");
  state_.resize_walls();
}

template void Simulation<double>::save_checkpoint(const std::filesystem::path &) const;
template void Simulation<float>::save_checkpoint(const std::filesystem::path &) const;
template void Simulation<double>::load_checkpoint(const std::filesystem::path &);
template void Simulation<float>::load_checkpoint(const std::filesystem::path &);

}  // namespace spreadmap::engine
