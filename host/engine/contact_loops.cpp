#include <engine/contact_loops.hpp>
#include <engine/history_values.hpp>
#include <engine/team.hpp>
#include <engine/thread_team.hpp>

#include <algorithm>
#include <spreadmap/geometry.hpp>
#include <spreadmap/simd.hpp>
#include <type_traits>

namespace spreadmap::engine {

namespace {
template <class Real> PairLaw<Real> pair_law(const ContactLaw &law) {
  if constexpr (std::is_same_v<Real, double>)
    return {law.ops->pair_queue_f64, law.self, Real(law_range(law)), law_history(law)};
  else return {law.ops->pair_queue_f32, law.self, Real(law_range(law)), law_history(law)};
}

// A queue of particles interacting with one wall, handed to the law when full or at the end.
template <class Real> struct WallBatch {
  static constexpr int capacity = 64;
  static constexpr int chunk = 16;  // records scanned between checks of the room left
  std::uint32_t i[capacity + chunk];
  Real f[6 * capacity];  // force, then torque, `capacity` apart

  void flush(int size, const ContactLaw &law, const Particles<Real> &p, const WallContacts<Real> &w) {
    if (size == 0) return;
    const WallQueue<Real> q{std::uint32_t(size), std::uint32_t(capacity), i, f};
    if constexpr (std::is_same_v<Real, double>) law.ops->wall_queue_f64(law.self, &p, &w, &q);
    else law.ops->wall_queue_f32(law.self, &p, &w, &q);
    for (int k = 0; k < size; ++k) {
      const std::uint32_t at = i[k];
      p.fx[at] += f[k];
      p.fy[at] += f[capacity + k];
      p.fz[at] += f[2 * capacity + k];
      p.tx[at] += f[3 * capacity + k];
      p.ty[at] += f[4 * capacity + k];
      p.tz[at] += f[5 * capacity + k];
    }
  }
};

// The records [lo, hi) of one wall: those above the floor queued (without a branch where no history is
// kept), the history of the others cleared.
template <class Real>
void wall_range(const ContactLaw &law, const Particles<Real> &p, const WallContacts<Real> &w, Real floor,
                unsigned history, std::uint32_t lo, std::uint32_t hi) {
  using Batch = WallBatch<Real>;
  Batch batch;
  int queued = 0;
  for (std::uint32_t k = lo; k < hi;) {
    const std::uint32_t stop = std::min(hi, k + std::uint32_t(Batch::chunk));
    if (history == 0) {
      for (; k < stop; ++k) {
        batch.i[queued] = k;
        queued += w.overlap[k] > floor ? 1 : 0;
      }
    } else {
      for (; k < stop; ++k) {
        batch.i[queued] = k;
        if (w.overlap[k] > floor) ++queued;
        else if (Real *h = w.hist + std::size_t(k) * history; any_value(h, history))
          std::fill_n(h, history, Real(0));  // apart: forget (most hold nothing: a read, not a write)
      }
    }
    if (queued > Batch::capacity - Batch::chunk) {
      batch.flush(queued, law, p, w);
      queued = 0;
    }
  }
  batch.flush(queued, law, p, w);
}
}  // namespace

template <class Real>
void pair_forces(const ContactLaw &law, const Particles<Real> &p, const ListView<Real> &list, PairSideJob side) {
  if (takes_ranges(law) && list.once() && law_pairs_once(law)) {
    pair_forces_once(pair_law<Real>(law), p, list, side);  // runs the side job in its own run
    return;
  }
  if (takes_ranges(law)) {
    pair_forces_every_entry(pair_law<Real>(law), p, list);
  } else {
    const PairList<Real> whole = list.whole();
    if constexpr (std::is_same_v<Real, double>) law.ops->pairs_f64(law.self, &p, &whole);
    else law.ops->pairs_f32(law.self, &p, &whole);
  }
  if (side.run) side.run(side.arg, 0, p.n);
}

namespace {
// The floor above which a wall record interacts with `law`: its range, or the wall's gap when smaller.
template <class Real> Real wall_floor(const ContactLaw &law, const WallContacts<Real> &w) {
  const Real range = Real(law_range(law));
  return range > 0 ? Real(0) - std::min(w.gap, range) : Real(0);
}
}  // namespace

template <class Real> void wall_forces(const ContactLaw &law, const Particles<Real> &p, const WallContacts<Real> &w) {
  if (!takes_ranges(law)) {
    if constexpr (std::is_same_v<Real, double>) law.ops->walls_f64(law.self, &p, &w);
    else law.ops->walls_f32(law.self, &p, &w);
    return;
  }
  const Real floor = wall_floor(law, w);
  const unsigned history = law_history(law);
  run_team(this_thread_team(), [&](TeamSlot team) {
    const TeamRange r = team_share(w.n, team);
    with_simd([&] {
      wall_range(law, p, w, floor, history, static_cast<std::uint32_t>(r.lo), static_cast<std::uint32_t>(r.hi));
    });
  });
}

template <class Real>
void wall_forces_range(const ContactLaw &law, const Particles<Real> &p, const WallContacts<Real> &w, std::uint32_t lo,
                       std::uint32_t hi) {
  const Real floor = wall_floor(law, w);
  const unsigned history = law_history(law);
  with_simd([&] { wall_range(law, p, w, floor, history, lo, hi); });
}

template <class Real>
void geometry_contacts_range(const GeometryWall &geometry, const Particles<Real> &p, WallContacts<Real> &w,
                             std::uint32_t lo, std::uint32_t hi) {
  if constexpr (std::is_same_v<Real, double>) geometry.ops->contacts_range_f64(geometry.self, &p, &w, lo, hi);
  else geometry.ops->contacts_range_f32(geometry.self, &p, &w, lo, hi);
}

template <class Real>
void geometry_contacts(const GeometryWall &geometry, const Particles<Real> &p, WallContacts<Real> &w) {
  if (!takes_ranges(geometry)) {
    if constexpr (std::is_same_v<Real, double>) geometry.ops->contacts_f64(geometry.self, &p, &w);
    else geometry.ops->contacts_f32(geometry.self, &p, &w);
    return;
  }
  run_team(this_thread_team(), [&](TeamSlot team) {
    const TeamRange r = team_share(p.n, team);
    geometry_contacts_range(geometry, p, w, static_cast<std::uint32_t>(r.lo), static_cast<std::uint32_t>(r.hi));
  });
}

template void pair_forces(const ContactLaw &, const Particles<double> &, const ListView<double> &, PairSideJob);
template void pair_forces(const ContactLaw &, const Particles<float> &, const ListView<float> &, PairSideJob);
template void wall_forces(const ContactLaw &, const Particles<double> &, const WallContacts<double> &);
template void wall_forces(const ContactLaw &, const Particles<float> &, const WallContacts<float> &);
template void geometry_contacts(const GeometryWall &, const Particles<double> &, WallContacts<double> &);
template void geometry_contacts(const GeometryWall &, const Particles<float> &, WallContacts<float> &);
template void wall_forces_range(const ContactLaw &, const Particles<double> &, const WallContacts<double> &,
                                std::uint32_t, std::uint32_t);
template void wall_forces_range(const ContactLaw &, const Particles<float> &, const WallContacts<float> &,
                                std::uint32_t, std::uint32_t);
template void geometry_contacts_range(const GeometryWall &, const Particles<double> &, WallContacts<double> &,
                                      std::uint32_t, std::uint32_t);
template void geometry_contacts_range(const GeometryWall &, const Particles<float> &, WallContacts<float> &,
                                      std::uint32_t, std::uint32_t);

}  // namespace spreadmap::engine
