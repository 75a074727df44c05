#pragma once
// The state and steps of the random packing's radius expansion with overlap relaxation
// (packing_random.h describes the algorithm; packing_random.cc drives it): final radii R,
// current radii s R and centres x, FIRE relaxation on the harmonic overlap energy (unit
// stiffness and masses, overlap_forces.h), growth, shrinking and the random removal of spheres.
// Internal to packing_random.cc.
#include "dem/packing/cell_list.h"
#include "dem/packing/overlap_forces.h"
#include "dem/packing/packing_random.h"
#include "dem/packing/packing_rng.h"
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace dembridge::dem::packing_detail
{
/// The packing state: final radii R, current radii s R and centres x.
class Packer
{
public:
  Packer(const RandomPackingSettings& set, std::vector<double> radii, Rng& rng)
      : L_(set.box_size), R_(std::move(radii)), s_(set.initial_radius_fraction),
        rmean_(set.mean_radius), skin_(0.3 * set.mean_radius), vector_path_(set.vector_path)
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

  std::size_t size() const { return R_.size(); }
  double scale() const { return s_; }
  const std::vector<Vec3>& positions() const { return x_; }
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
    for (std::size_t i = 0; i < x_.size(); ++i)
      clamp(i);
  }

  /// Overlap forces f_i = sum_j delta_ij n_ji (unit stiffness, overlap_forces.h); returns the
  /// mean overlap per contact / mean radius and the largest overlap / smaller current radius.
  std::pair<double, double> forces()
  {
    update_list();
    const OverlapSums sums = overlap_.compute(pairs_, x_, s_, f_, vector_path_);
    return {sums.contacts ? sums.sum_overlap / double(sums.contacts) / (s_ * rmean_) : 0.0,
            sums.worst};
  }

  /// One FIRE step (Bitzek et al. 2006): mix the velocity towards the force while the power
  /// is positive, stop and shorten the step when it turns negative; symplectic Euler update,
  /// walls by projection.
  void fire_step()
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
      std::fill(v_.begin(), v_.end(), Vec3::Zero());
    }
    const double dt = dt_, s = s_;
    for (std::size_t i = 0; i < n; ++i)
    {
      if (P > 0)
        v[i] = mix * v[i] + c * f[i];
      v[i] += dt * f[i];
      x[i] += dt * v[i];
      clamp(x[i], v[i], s * R_[i]);
    }
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
    reset_fire();
    return removed;
  }

private:
  Vec3 L_;
  std::vector<double> R_;
  double s_, rmean_, skin_, rmax_ = 0;
  bool vector_path_ = true;
  std::vector<Vec3> x_, xb_;          // centres, centres at the last list build
  double sb_ = 0;                     // s at the last list build
  OverlapPairs pairs_;                // Verlet pair list, in the cell list's order
  OverlapForces overlap_;             // the force kernel and its scratch
  std::vector<double> sorted_radius_; // radii in the cell list's slot order
  std::vector<Vec3> v_, f_;           // FIRE velocities and forces
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
      // why: four running maxima (max is exact in any order) let the loop pipeline
      double m[4] = {0, 0, 0, 0};
      const std::size_t n = x_.size(), n4 = n - n % 4;
      for (std::size_t i = 0; i < n4; i += 4)
        for (int k = 0; k < 4; ++k)
          m[k] = std::max(m[k], (x_[i + k] - xb_[i + k]).squaredNorm());
      for (std::size_t i = n4; i < n; ++i)
        m[0] = std::max(m[0], (x_[i] - xb_[i]).squaredNorm());
      const double d2 = std::max(std::max(m[0], m[1]), std::max(m[2], m[3]));
      // why: two spheres approach by at most twice the largest displacement plus their growth
      if (2 * std::sqrt(d2) + 2 * std::max(0.0, s_ - sb_) * rmax_ < skin_)
        return;
    }
    // The pairs within s (R_i + R_j) + skin, visited as CellList::for_each_pair visits them and
    // appended without branches: every candidate is written, the count advances only when it
    // qualifies (j > i, inside the cell size, inside the pair's reach).
    const CellList cells(x_, 2 * s_ * rmax_ + skin_);
    const double h2 = cells.cell_size() * cells.cell_size(), s = s_, skin = skin_;
    const int* slot_particle = cells.particle();
    const Vec3* slot_centre = cells.centre();
    sorted_radius_.resize(R_.size());
    for (std::size_t k = 0; k < R_.size(); ++k)
      sorted_radius_[k] = R_[slot_particle[k]];
    std::size_t np = 0;
    cells.for_each_neighbour_cell(
        [&](int i, const Vec3& xi, int begin, int end)
        {
          if (pairs_.i.size() < np + std::size_t(end - begin))
            pairs_.resize(2 * (np + std::size_t(end - begin)) + 64);
          const double Ri = R_[i];
          for (int k2 = begin; k2 < end; ++k2)
          {
            const int j = slot_particle[k2];
            const double Rj = sorted_radius_[k2], d2 = (slot_centre[k2] - xi).squaredNorm();
            const double radius_sum = Ri + Rj, lim = s * radius_sum + skin;
            pairs_.i[np] = i;
            pairs_.j[np] = j;
            pairs_.radius_sum[np] = radius_sum;
            pairs_.radius_min[np] = std::min(Ri, Rj);
            np += (j > i) & (d2 < h2) & (d2 < lim * lim);
          }
        });
    pairs_.resize(np);
    xb_ = x_;
    sb_ = s_;
  }

  void clamp(std::size_t i) { clamp(x_[i], v_[i], s_ * R_[i]); }

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
