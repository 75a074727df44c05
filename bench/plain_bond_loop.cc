#include "plain_bond_loop.h"
#include <algorithm>
#include <cmath>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace dembridge::bench
{
using dem::Vec3;

PlainBondLoop::PlainBondLoop(const dem::ParticleStore& p, const dem::BondStore& b, double dt,
                             int threads)
    : threads_(threads), dt_(dt), n_(p.size())
{
  x_ = p.position, v_ = p.velocity, w_ = p.angular_velocity;
  F_.assign(n_, Vec3::Zero()), M_.assign(n_, Vec3::Zero());
  for (std::size_t i = 0; i < n_; ++i)
    inv_m_.push_back(1.0 / p.mass[i]), inv_I_.push_back(1.0 / p.inertia[i]);
  const auto part = dem::partition_bonds_by_index(b.a, b.b, n_, threads);
  phases_ = part.phases;
  for (std::size_t k : part.order)
  {
    a_.push_back(b.a[k]), b_.push_back(b.b[k]);
    kn_.push_back(b.kn[k]), ks_.push_back(b.ks[k]), kt_.push_back(b.ktor[k]);
    kb_.push_back(b.kben[k]), s_.push_back(b.contact_fraction[k]);
    ct_.push_back(b.damping_force[k]), cr_.push_back(b.damping_moment[k]);
  }
  fn_.assign(a_.size(), 0.0), mt_.assign(a_.size(), 0.0);
  fs_.assign(a_.size(), Vec3::Zero()), mb_.assign(a_.size(), Vec3::Zero());
}

// Written out in scalars (as the full model's kernel), so the comparison is of the laws, not of
// the expression style.
void PlainBondLoop::bond_range(std::size_t begin, std::size_t end)
{
  const double dt = dt_;
  const double* X = x_[0].data();
  const double* V = v_[0].data();
  const double* W = w_[0].data();
  double* F = F_[0].data();
  double* M = M_[0].data();
  for (std::size_t k = begin; k < end; ++k)
  {
    const std::size_t ia = 3 * std::size_t(a_[k]), ib = 3 * std::size_t(b_[k]);
    const double dx = X[ib] - X[ia], dy = X[ib + 1] - X[ia + 1], dz = X[ib + 2] - X[ia + 2];
    const double iL = 1.0 / std::sqrt(dx * dx + dy * dy + dz * dz);
    const double nx = dx * iL, ny = dy * iL, nz = dz * iL;
    const double s = s_[k], t = s - 1.0;
    const double rax = s * dx, ray = s * dy, raz = s * dz; // x_c - x_a
    const double rbx = t * dx, rby = t * dy, rbz = t * dz; // x_c - x_b
    const double wax = W[ia], way = W[ia + 1], waz = W[ia + 2];
    const double wbx = W[ib], wby = W[ib + 1], wbz = W[ib + 2];
    const double vcx = V[ib] + (wby * rbz - wbz * rby) - V[ia] - (way * raz - waz * ray);
    const double vcy = V[ib + 1] + (wbz * rbx - wbx * rbz) - V[ia + 1] - (waz * rax - wax * raz);
    const double vcz = V[ib + 2] + (wbx * rby - wby * rbx) - V[ia + 2] - (wax * ray - way * rax);
    const double wrx = wbx - wax, wry = wby - way, wrz = wbz - waz;
    const double vn = vcx * nx + vcy * ny + vcz * nz, wn = wrx * nx + wry * ny + wrz * nz;
    const double kdt = ks_[k] * dt, bdt = kb_[k] * dt;
    double* fs = fs_[k].data();
    double* mb = mb_[k].data();
    const double fsn = fs[0] * nx + fs[1] * ny + fs[2] * nz;
    const double mbn = mb[0] * nx + mb[1] * ny + mb[2] * nz;
    fs[0] -= fsn * nx + kdt * (vcx - vn * nx);
    fs[1] -= fsn * ny + kdt * (vcy - vn * ny);
    fs[2] -= fsn * nz + kdt * (vcz - vn * nz);
    mb[0] -= mbn * nx + bdt * (wrx - wn * nx);
    mb[1] -= mbn * ny + bdt * (wry - wn * ny);
    mb[2] -= mbn * nz + bdt * (wrz - wn * nz);
    const double fn = fn_[k] -= kn_[k] * vn * dt;
    const double mt = mt_[k] -= kt_[k] * wn * dt;
    const double ct = ct_[k], cr = cr_[k];
    const double fx = fn * nx + fs[0] - ct * vcx, fy = fn * ny + fs[1] - ct * vcy,
                 fz = fn * nz + fs[2] - ct * vcz;
    const double mx = mt * nx + mb[0] - cr * wrx, my = mt * ny + mb[1] - cr * wry,
                 mz = mt * nz + mb[2] - cr * wrz;
    F[ia] -= fx, F[ia + 1] -= fy, F[ia + 2] -= fz;
    F[ib] += fx, F[ib + 1] += fy, F[ib + 2] += fz;
    M[ia] += -mx - (ray * fz - raz * fy);
    M[ia + 1] += -my - (raz * fx - rax * fz);
    M[ia + 2] += -mz - (rax * fy - ray * fx);
    M[ib] += mx + (rby * fz - rbz * fy);
    M[ib + 1] += my + (rbz * fx - rbx * fz);
    M[ib + 2] += mz + (rbx * fy - rby * fx);
  }
}

void PlainBondLoop::step()
{
  for (int phase = 0; phase < 3; ++phase)
  {
    const auto& ranges = phases_[phase];
#pragma omp parallel for num_threads(threads_) schedule(static, 1)
    for (std::size_t r = 0; r < ranges.size(); ++r)
      bond_range(ranges[r].first, ranges[r].second);
  }
  for (const auto& r : phases_[3])
    bond_range(r.first, r.second);
  const double dt = dt_;
  const long n = long(n_);
#pragma omp parallel for num_threads(threads_) schedule(static)
  for (long i = 0; i < n; ++i)
  {
    v_[i] += (dt * inv_m_[i]) * F_[i];
    w_[i] += (dt * inv_I_[i]) * M_[i];
    x_[i] += dt * v_[i];
    F_[i].setZero();
    M_[i].setZero();
  }
}

double PlainBondLoop::max_speed() const
{
  double v2 = 0;
  for (const auto& v : v_)
    v2 = std::max(v2, v.squaredNorm());
  return std::sqrt(v2);
}

std::size_t PlainBondLoop::memory_bytes() const
{
  std::size_t bytes = 0;
  for (const auto* v : {&x_, &v_, &w_, &F_, &M_, &fs_, &mb_})
    bytes += v->capacity() * sizeof(Vec3);
  for (const auto* v : {&inv_m_, &inv_I_, &kn_, &ks_, &kt_, &kb_, &s_, &ct_, &cr_, &fn_, &mt_})
    bytes += v->capacity() * sizeof(double);
  return bytes + (a_.capacity() + b_.capacity()) * sizeof(std::int32_t);
}
} // namespace dembridge::bench
