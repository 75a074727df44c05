#pragma once
// The state and steps of the random packing's radius expansion with overlap relaxation
// (packing_random.h describes the algorithm; packing_random.cc drives it): final radii R,
// current radii s R and centres x, FIRE relaxation on the harmonic overlap energy (unit
// stiffness and masses, overlap_forces.h), growth, shrinking and the random removal of spheres.
// Internal to packing_random.cc.
#include "dem/core/simd_gather.h"
#include "dem/packing/cell_list.h"
#include "dem/packing/overlap_forces.h"
#include "dem/packing/packing_random.h"
#include "dem/packing/packing_rng.h"
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>
#if defined(_OPENMP)
#include <omp.h>
#endif

namespace dembridge::dem::packing_detail
{
/// The packing state: final radii R, current radii s R and centres x.
class Packer
{
public:
  Packer(const RandomPackingSettings& set, std::vector<double> radii, Rng& rng)
      : L_(set.box_size), R_(std::move(radii)), s_(set.initial_radius_fraction),
        rmean_(set.mean_radius), skin_(0.3 * set.mean_radius), vector_path_(set.vector_path),
#if defined(_OPENMP)
        threads_(std::max(1, set.threads))
#else
        threads_(1)
#endif
  {
    x_.resize(R_.size());
    for (std::size_t i = 0; i < R_.size(); ++i)
    {
      const double a = s_ * R_[i];
      for (int d = 0; d < 3; ++d)
        x_[i][d] = a + (L_[d] - 2 * a) * rng.uniform();
    }
    spatial_sort();
    reset_fire();
    rmax_ = *std::max_element(R_.begin(), R_.end());
  }

  std::size_t size() const
  {
    return R_.size();
  }
  double scale() const
  {
    return s_;
  }
  const std::vector<Vec3>& positions() const
  {
    return x_;
  }
  /// Sum of R_i^3.
  double volume() const
  {
    double v = 0;
    for (double r : R_)
      v += r * r * r;
    return v;
  }

  /// The current radii s R_i.
  std::vector<double> final_radii() const
  {
    std::vector<double> r(R_);
    for (double& ri : r)
      ri *= s_;
    return r;
  }

  /// Sets the radius scale s and puts the spheres back inside the walls.
  void set_scale(double s)
  {
    s_ = s;
    displacement2_ = -1; // why: the clamps move spheres
    const long n = long(x_.size());
#pragma omp parallel for num_threads(threads_) schedule(static) if (x_.size() > parallel_min_)
    for (long i = 0; i < n; ++i)
      clamp(std::size_t(i));
  }

  /// Overlap forces f_i = sum_j delta_ij n_ji (unit stiffness, overlap_forces.h); returns the
  /// mean overlap per contact / mean radius and the largest overlap / smaller current radius,
  /// either of which may be NaN when not asked for (saving a serial sum or a division a contact).
  std::pair<double, double> forces(bool need_mean = true, bool need_worst = true)
  {
    update_list();
    const OverlapSums sums =
        overlap_.compute(pairs_, x_, s_, f_, vector_path_, x_.size() > parallel_min_ ? threads_ : 1,
                         need_mean, need_worst);
    return {sums.contacts ? sums.sum_overlap / double(sums.contacts) / (s_ * rmean_) : 0.0,
            sums.worst};
  }

  /// One FIRE step (Bitzek et al. 2006): mix the velocity towards the force while the power
  /// is positive, stop and shorten the step when it turns negative; symplectic Euler update,
  /// walls by projection. Then, if next_scale >= 0, set_scale(next_scale) in the same pass.
  void fire_step(double next_scale = -1)
  {
    const std::size_t n = x_.size();
    Vec3* const x = x_.data();
    Vec3* const v = v_.data();
    const Vec3* const f = f_.data();
    double P = 0, vv = 0, ff = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
      P += f[i].dot(v[i]);
      vv += v[i].squaredNorm();
      ff += f[i].squaredNorm();
    }
    // why: one pass over the spheres for the velocity mixing, the update and the walls (each
    // sphere's arithmetic is the same as in separate passes)
    double mix = 1, c = 0;
    if (P > 0)
    {
      mix = 1 - alpha_;
      c = ff > 0 ? alpha_ * std::sqrt(vv / ff) : 0;
      if (++npos_ > 5)
      {
        dt_ = std::min(dt_ * 1.1, dt_max_);
        alpha_ *= 0.99;
      }
    }
    else
    {
      npos_ = 0;
      dt_ = std::max(dt_ * 0.5, dt_min_);
      alpha_ = alpha0_;
    }
    const double dt = dt_, s = s_, s_next = next_scale >= 0 ? next_scale : s_;
    s_ = s_next;
    // why: one pass (one parallel region) for the velocity mixing or reset, the update, the
    // walls at the old and the new scale, and the largest displacement since the last list
    // build, which update_list then needs not compute (each sphere's arithmetic and every max
    // are those of separate passes)
    const bool track = xb_.size() == n;
    const Vec3* const xb = xb_.data();
    // why: the spheres past the vector blocks (all of them without AVX-512) one at a time
    std::size_t n_vector = 0;
#if defined(__AVX512F__)
    if (vector_path_)
      n_vector = n - n % 8;
#endif
    const long nl = long(n), first_scalar = long(n_vector);
    [[maybe_unused]] const long blocks = long(n_vector / 8);
    double d2 = 0;
    // clang-format off
#pragma omp parallel num_threads(threads_) if (n > parallel_min_) reduction(max : d2)
    // clang-format on
    {
#if defined(__AVX512F__)
#pragma omp for schedule(static) nowait
      for (long block = 0; block < blocks; ++block)
        d2 = std::max(
            d2, fire_update_block(std::size_t(block) * 8, P > 0, mix, c, dt, s, s_next, track));
#endif
#pragma omp for schedule(static)
      for (long i = first_scalar; i < nl; ++i)
      {
        if (P > 0)
          v[i] = mix * v[i] + c * f[i];
        else
          v[i] = Vec3::Zero();
        v[i] += dt * f[i];
        x[i] += dt * v[i];
        clamp(x[i], v[i], s * R_[i]);
        if (s_next != s)
          clamp(x[i], v[i], s_next * R_[i]);
        if (track)
          d2 = std::max(d2, (x[i] - xb[i]).squaredNorm());
      }
    }
    displacement2_ = track ? d2 : -1;
  }

  void reset_fire()
  {
    dt_ = dt0_;
    alpha_ = alpha0_;
    npos_ = 0;
    v_.assign(x_.size(), Vec3::Zero());
    f_.assign(x_.size(), Vec3::Zero());
  }

  /// Removes random spheres until sum R^3 <= keep (fraction of the current sum).
  std::size_t remove_random(double keep, Rng& rng)
  {
    double sum = 0;
    for (double r : R_)
      sum += r * r * r;
    const double target = keep * sum;
    std::vector<char> gone(R_.size(), 0);
    std::size_t removed = 0;
    while (sum > target && removed + 1 < R_.size())
    {
      const std::size_t i = rng.index(R_.size());
      if (gone[i])
        continue;
      gone[i] = 1;
      sum -= R_[i] * R_[i] * R_[i];
      ++removed;
    }
    std::size_t k = 0;
    for (std::size_t i = 0; i < R_.size(); ++i)
      if (!gone[i])
      {
        x_[k] = x_[i];
        R_[k] = R_[i];
        ++k;
      }
    x_.resize(k);
    R_.resize(k);
    xb_.clear(); // forces a list rebuild
    displacement2_ = -1;
    reset_fire();
    return removed;
  }

private:
  Vec3 L_;
  std::vector<double> R_;
  double s_, rmean_, skin_, rmax_ = 0;
  bool vector_path_ = true;
  int threads_ = 1;
  // why: below this many spheres a sweep (~0.1 ms) is too short to pay for waking a second
  // thread (two threads against one, best / median of 7 alternating rounds on this VM: 669
  // spheres 1.01x / 0.88x, 1,283 spheres 1.19x / 1.07x, 2,874 spheres 1.31x / 1.26x)
  static constexpr std::size_t parallel_min_ = 1000;
  std::vector<Vec3> x_, xb_;  // centres, centres at the last list build
  double sb_ = 0;             // s at the last list build
  double displacement2_ = -1; // largest |x - xb|^2 after the last FIRE step; < 0: unknown
  OverlapPairs pairs_;        // Verlet pair list, in the cell list's order
  std::vector<OverlapPairs> chunk_pairs_; // threads 1, 2, ...: their layers' pairs
  std::vector<std::size_t> chunk_size_;   // pairs collected by each thread
  OverlapForces overlap_;                 // the force kernel and its scratch
  std::vector<double> sorted_radius_;     // radii in the cell list's slot order
  std::vector<Vec3> v_, f_;               // FIRE velocities and forces
  // FIRE parameters (Bitzek et al. 2006) in dimensionless time (unit stiffness and mass): the
  // stiffest mode of ~12 unit springs per sphere needs dt < 2/sqrt(24) ~ 0.4.
  static constexpr double dt0_ = 0.1, dt_max_ = 0.3, dt_min_ = 0.005, alpha0_ = 0.1;
  double dt_ = dt0_, alpha_ = alpha0_;
  int npos_ = 0;

  /// Rebuilds the Verlet pair list when a pair outside it could have come into contact.
  void update_list()
  {
    if (xb_.size() == x_.size())
    {
      double d2 = displacement2_; // from the last FIRE step, if nothing moved since
      if (d2 < 0)
      {
        // why: four running maxima (max is exact in any order) let the loop pipeline
        const std::size_t n = x_.size(), n4 = n - n % 4;
        d2 = 0;
#pragma omp parallel num_threads(threads_) reduction(max : d2) if (n > parallel_min_)
        {
          double m[4] = {0, 0, 0, 0};
#pragma omp for schedule(static)
          for (long i = 0; i < long(n4); i += 4)
            for (int k = 0; k < 4; ++k)
              m[k] = std::max(m[k], (x_[i + k] - xb_[i + k]).squaredNorm());
          d2 = std::max(std::max(m[0], m[1]), std::max(m[2], m[3]));
        }
        for (std::size_t i = n4; i < n; ++i)
          d2 = std::max(d2, (x_[i] - xb_[i]).squaredNorm());
      }
      // why: two spheres approach by at most twice the largest displacement plus their growth
      if (2 * std::sqrt(d2) + 2 * std::max(0.0, s_ - sb_) * rmax_ < skin_)
        return;
    }
    // The pairs within s (R_i + R_j) + skin in CellList::for_each_pair's order: each thread
    // collects the pairs of a range of cell layers, and the ranges are joined in order.
    const CellList cells(x_, 2 * s_ * rmax_ + skin_);
    const int* slot_particle = cells.particle();
    const long nr = long(R_.size());
    sorted_radius_.resize(R_.size());
    const int nt = int(std::min<long>(cells.layers(), R_.size() > parallel_min_ ? threads_ : 1));
    chunk_pairs_.resize(std::size_t(nt));
    chunk_size_.assign(std::size_t(nt), 0);
#pragma omp parallel num_threads(nt)
    {
#pragma omp for schedule(static)
      for (long k = 0; k < nr; ++k)
        sorted_radius_[k] = R_[slot_particle[k]];
#if defined(_OPENMP)
      const int t = omp_get_thread_num();
#else
      const int t = 0;
#endif
      const long layers = cells.layers();
      // why: thread 0 collects straight into the list; the others' pairs are appended after
      OverlapPairs& out = t == 0 ? pairs_ : chunk_pairs_[std::size_t(t)];
      chunk_size_[std::size_t(t)] =
          collect_pairs(cells, out, layers * t / nt, layers * (t + 1) / nt);
#pragma omp barrier
#pragma omp single
      {
        std::size_t total = 0;
        for (std::size_t size : chunk_size_)
          total += size;
        pairs_.resize(total);
      }
      if (t > 0)
      {
        std::size_t at = 0;
        for (int u = 0; u < t; ++u)
          at += chunk_size_[std::size_t(u)];
        const std::size_t m = chunk_size_[std::size_t(t)];
        std::copy_n(out.i.begin(), m, pairs_.i.begin() + long(at));
        std::copy_n(out.j.begin(), m, pairs_.j.begin() + long(at));
        std::copy_n(out.radius_sum.begin(), m, pairs_.radius_sum.begin() + long(at));
        std::copy_n(out.radius_min.begin(), m, pairs_.radius_min.begin() + long(at));
      }
    }
    xb_ = x_;
    sb_ = s_;
    displacement2_ = -1;
  }

  /// Collects the Verlet pairs of the cell layers [z_begin, z_end) into `out` (grown as
  /// needed; its size is left larger than the count) and returns their count. Appended without
  /// branches: every candidate is written, the count advances only when it qualifies (j > i,
  /// inside the cell size, inside the pair's reach).
  std::size_t collect_pairs(const CellList& cells, OverlapPairs& out, long z_begin,
                            long z_end) const
  {
    const double h2 = cells.cell_size() * cells.cell_size(), s = s_, skin = skin_;
    const int* slot_particle = cells.particle();
    const Vec3* slot_centre = cells.centre();
    std::size_t np = 0;
    cells.for_each_neighbour_cell(
        [&](int i, const Vec3& xi, int begin, int end)
        {
          // why: 8 spare slots, which the vector path's full-width stores may write
          if (out.i.size() < np + std::size_t(end - begin) + 8)
            out.resize(2 * (np + std::size_t(end - begin)) + 64);
          const double Ri = R_[i];
#if defined(__AVX512F__) && defined(__AVX512VL__)
          if (vector_path_)
          {
            np = collect_row(i, xi, Ri, begin, end, slot_particle, slot_centre, h2, out, np);
            return;
          }
#endif
          for (int k2 = begin; k2 < end; ++k2)
          {
            const int j = slot_particle[k2];
            const double Rj = sorted_radius_[k2], d2 = (slot_centre[k2] - xi).squaredNorm();
            const double radius_sum = Ri + Rj, lim = s * radius_sum + skin;
            out.i[np] = i;
            out.j[np] = j;
            out.radius_sum[np] = radius_sum;
            out.radius_min[np] = std::min(Ri, Rj);
            np += (j > i) & (d2 < h2) & (d2 < lim * lim);
          }
        },
        z_begin, z_end);
    return np;
  }

#if defined(__AVX512F__) && defined(__AVX512VL__)
  /// collect_pairs' filter on the slots [begin, end) of a row, eight candidates at a time: the
  /// same tests on the same correctly rounded values (this file is built without fused
  /// multiply-adds), the pairs that pass packed in slot order: the same list as the scalar loop.
  std::size_t collect_row(int i, const Vec3& xi, double Ri, int begin, int end,
                          const int* slot_particle, const Vec3* slot_centre, double h2,
                          OverlapPairs& out, std::size_t np) const
  {
    const double* centres = slot_centre[0].data();
    const __m512d vxi = _mm512_set1_pd(xi[0]), vyi = _mm512_set1_pd(xi[1]),
                  vzi = _mm512_set1_pd(xi[2]), vRi = _mm512_set1_pd(Ri);
    const __m512d vh2 = _mm512_set1_pd(h2), vs = _mm512_set1_pd(s_), vskin = _mm512_set1_pd(skin_);
    const __m256i vi = _mm256_set1_epi32(i);
    for (int k2 = begin; k2 < end; k2 += 8)
    {
      const int live_count = std::min(8, end - k2);
      const __mmask8 live = __mmask8((1u << live_count) - 1);
      std::int32_t slot[8];
      for (int q = 0; q < 8; ++q) // lanes past the row repeat its last slot (masked off below)
        slot[q] = k2 + std::min(q, live_count - 1);
      alignas(64) double c[4][8];
      gather_rows<8, 3>(centres, slot, c);
      const __m256i vj = _mm256_maskz_loadu_epi32(live, slot_particle + k2);
      const __m512d Rj = _mm512_maskz_loadu_pd(live, sorted_radius_.data() + k2);
      const __m512d dx = _mm512_sub_pd(_mm512_load_pd(c[0]), vxi);
      const __m512d dy = _mm512_sub_pd(_mm512_load_pd(c[1]), vyi);
      const __m512d dz = _mm512_sub_pd(_mm512_load_pd(c[2]), vzi);
      // (dx^2 + dy^2) + dz^2, as Eigen's squaredNorm sums
      const __m512d d2 = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)),
                                       _mm512_mul_pd(dz, dz));
      const __m512d radius_sum = _mm512_add_pd(vRi, Rj);
      const __m512d lim = _mm512_add_pd(_mm512_mul_pd(vs, radius_sum), vskin);
      // std::min(Ri, Rj) is Rj if Rj < Ri, else Ri
      const __m512d radius_min =
          _mm512_mask_blend_pd(_mm512_cmp_pd_mask(Rj, vRi, _CMP_LT_OQ), vRi, Rj);
      __mmask8 keep = _mm256_mask_cmpgt_epi32_mask(live, vj, vi);
      keep = _mm512_mask_cmp_pd_mask(keep, d2, vh2, _CMP_LT_OQ);
      keep = _mm512_mask_cmp_pd_mask(keep, d2, _mm512_mul_pd(lim, lim), _CMP_LT_OQ);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(out.i.data() + np), vi);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(out.j.data() + np),
                          _mm256_maskz_compress_epi32(keep, vj));
      _mm512_storeu_pd(out.radius_sum.data() + np, _mm512_maskz_compress_pd(keep, radius_sum));
      _mm512_storeu_pd(out.radius_min.data() + np, _mm512_maskz_compress_pd(keep, radius_min));
      np += std::size_t(__builtin_popcount(keep));
    }
    return np;
  }
#endif

#if defined(__AVX512F__)
  /// fire_step's update of the spheres i0 .. i0 + 7, their x, v and f read as three vectors of
  /// eight doubles each (x0 y0 z0 x1 ...): every component's arithmetic is the scalar loop's, in
  /// the same order (this file is built without fused multiply-adds), the walls by masks.
  /// Returns the largest |x - x_b|^2 of the eight (0 unless track).
  double fire_update_block(std::size_t i0, bool mixing, double mix, double c, double dt, double s,
                           double s_next, bool track)
  {
    double* const x = x_[i0].data();
    double* const v = v_[i0].data();
    const double* const f = f_[i0].data();
    // lane k of vector r holds component (8 r + k) % 3 of sphere i0 + (8 r + k) / 3
    const __m512i sphere[3] = {_mm512_set_epi64(2, 2, 1, 1, 1, 0, 0, 0),
                               _mm512_set_epi64(5, 4, 4, 4, 3, 3, 3, 2),
                               _mm512_set_epi64(7, 7, 7, 6, 6, 6, 5, 5)};
    const __m512i axis[3] = {_mm512_set_epi64(1, 0, 2, 1, 0, 2, 1, 0),
                             _mm512_set_epi64(0, 2, 1, 0, 2, 1, 0, 2),
                             _mm512_set_epi64(2, 1, 0, 2, 1, 0, 2, 1)};
    const __m512d box = _mm512_set_pd(0, 0, 0, 0, 0, L_[2], L_[1], L_[0]);
    const __m512d radii = _mm512_loadu_pd(R_.data() + i0), zero = _mm512_setzero_pd();
    const __m512d vmix = _mm512_set1_pd(mix), vc = _mm512_set1_pd(c), vdt = _mm512_set1_pd(dt);
    // the walls' projection (clamp): below a, x = a and v = max(v, 0); else above L - a,
    // x = L - a and v = min(v, 0) (max_pd(0, v) and min_pd(0, v) return v for v = +-0 and NaN,
    // as std::max(v, 0.0) and std::min(v, 0.0) do)
    auto clamp_lanes = [&](__m512d& xr, __m512d& vr, __m512d a, __m512d L)
    {
      const __mmask8 below = _mm512_cmp_pd_mask(xr, a, _CMP_LT_OQ);
      const __m512d upper = _mm512_sub_pd(L, a);
      const __mmask8 above = _mm512_mask_cmp_pd_mask(__mmask8(~below), xr, upper, _CMP_GT_OQ);
      xr = _mm512_mask_blend_pd(below, xr, a);
      vr = _mm512_mask_blend_pd(below, vr, _mm512_max_pd(zero, vr));
      xr = _mm512_mask_blend_pd(above, xr, upper);
      vr = _mm512_mask_blend_pd(above, vr, _mm512_min_pd(zero, vr));
    };
    __m512d sq[3];
    for (int r = 0; r < 3; ++r)
    {
      const __m512d fr = _mm512_loadu_pd(f + 8 * r);
      __m512d vr = mixing ? _mm512_add_pd(_mm512_mul_pd(vmix, _mm512_loadu_pd(v + 8 * r)),
                                          _mm512_mul_pd(vc, fr))
                          : zero;
      vr = _mm512_add_pd(vr, _mm512_mul_pd(vdt, fr));
      __m512d xr = _mm512_add_pd(_mm512_loadu_pd(x + 8 * r), _mm512_mul_pd(vdt, vr));
      const __m512d R = _mm512_permutexvar_pd(sphere[r], radii);
      const __m512d L = _mm512_permutexvar_pd(axis[r], box);
      clamp_lanes(xr, vr, _mm512_mul_pd(_mm512_set1_pd(s), R), L);
      if (s_next != s)
        clamp_lanes(xr, vr, _mm512_mul_pd(_mm512_set1_pd(s_next), R), L);
      _mm512_storeu_pd(v + 8 * r, vr);
      _mm512_storeu_pd(x + 8 * r, xr);
      if (track)
      {
        const __m512d d = _mm512_sub_pd(xr, _mm512_loadu_pd(xb_[i0].data() + 8 * r));
        sq[r] = _mm512_mul_pd(d, d);
      }
    }
    if (!track)
      return 0;
    // the squares by axis (lanes = spheres), then (dx^2 + dy^2) + dz^2 as squaredNorm sums
    auto by_axis = [&](__m512i from01, __m512i from2)
    { return _mm512_permutex2var_pd(_mm512_permutex2var_pd(sq[0], from01, sq[1]), from2, sq[2]); };
    const __m512d sx = by_axis(_mm512_set_epi64(0, 0, 15, 12, 9, 6, 3, 0),
                               _mm512_set_epi64(13, 10, 5, 4, 3, 2, 1, 0));
    const __m512d sy = by_axis(_mm512_set_epi64(0, 0, 0, 13, 10, 7, 4, 1),
                               _mm512_set_epi64(14, 11, 8, 4, 3, 2, 1, 0));
    const __m512d sz = by_axis(_mm512_set_epi64(0, 0, 0, 14, 11, 8, 5, 2),
                               _mm512_set_epi64(15, 12, 9, 4, 3, 2, 1, 0));
    return _mm512_reduce_max_pd(_mm512_add_pd(_mm512_add_pd(sx, sy), sz));
  }
#endif

  void clamp(std::size_t i)
  {
    clamp(x_[i], v_[i], s_ * R_[i]);
  }

  /// Puts a sphere of radius a back inside the walls; the wall takes its outward velocity.
  void clamp(Vec3& x, Vec3& v, double a) const
  {
    for (int d = 0; d < 3; ++d)
    {
      if (x[d] < a)
      {
        x[d] = a;
        v[d] = std::max(v[d], 0.0);
      }
      else if (x[d] > L_[d] - a)
      {
        x[d] = L_[d] - a;
        v[d] = std::min(v[d], 0.0);
      }
    }
  }

  /// Orders the spheres along a coarse z-y-x cell grid so that neighbours sit close in memory.
  void spatial_sort()
  {
    const double h = 4 * rmean_;
    long n[3];
    for (int d = 0; d < 3; ++d)
      n[d] = std::max(1L, long(L_[d] / h) + 1);
    std::vector<std::pair<long, std::size_t>> key(x_.size());
    for (std::size_t i = 0; i < x_.size(); ++i)
    {
      long c[3];
      for (int d = 0; d < 3; ++d)
        c[d] = std::clamp(long(x_[i][d] / h), 0L, n[d] - 1);
      key[i] = {(c[2] * n[1] + c[1]) * n[0] + c[0], i};
    }
    std::sort(key.begin(), key.end()); // why: (cell, index) is a total order: deterministic
    std::vector<Vec3> x(x_.size());
    std::vector<double> r(R_.size());
    for (std::size_t k = 0; k < key.size(); ++k)
    {
      x[k] = x_[key[k].second];
      r[k] = R_[key[k].second];
    }
    x_ = std::move(x);
    R_ = std::move(r);
  }
};
} // namespace dembridge::dem::packing_detail
