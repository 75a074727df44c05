#pragma once
// The random packing's overlap forces (packing_random.h): for every Verlet pair (i, j) of spheres
// with current radii s R_i, s R_j and centre distance d = |x_j - x_i|, the overlap
//   delta_ij = s (R_i + R_j) - d   (pairs with delta > 0 only)
// pushes the two apart along n = (x_j - x_i) / d with unit stiffness:
//   f_i -= delta n,   f_j += delta n
// (the gradient of the harmonic overlap energy 1/2 sum delta^2; coincident centres are separated
// along x). Also returned: the sum of the overlaps, their count and the largest
// delta / (s min(R_i, R_j)).
//
// The sums run over the pairs in list order, one contact at a time, whatever the path, so every
// floating-point result is fixed by the list: the vector path (AVX-512, where the CPU has it)
// only computes the pairs' terms eight at a time with the same correctly rounded operations.
// Included only by packing_random.cc, which is built without fused multiply-adds
// (dem/CMakeLists.txt), so both paths give bitwise the same packing on every CPU.
#include "dem/core/types.h"
#include <algorithm>
#include <cmath>
#include <vector>
#if defined(__AVX512F__)
#include <immintrin.h>
#endif

namespace dembridge::dem
{
/// A Verlet pair list as arrays: the pairs' sphere indices, radius sums and smaller radii.
struct OverlapPairs
{
  std::vector<int> i, j;
  std::vector<double> radius_sum, radius_min;
  void resize(std::size_t n)
  {
    i.resize(n);
    j.resize(n);
    radius_sum.resize(n);
    radius_min.resize(n);
  }
};

struct OverlapSums
{
  double sum_overlap = 0; ///< sum of delta over the contacts
  double worst = 0;       ///< largest delta / (s min(R_i, R_j))
  long contacts = 0;      ///< pairs with delta > 0
};

/// The force kernel with its scratch buffers (kept between calls: no allocation per sweep).
class OverlapForces
{
public:
  /// f_out = the overlap forces of the pairs at radius scale s (f_out sized like x_in).
  OverlapSums compute(const OverlapPairs& pairs, const std::vector<Vec3>& x_in, double s,
                      std::vector<Vec3>& f_out, bool vector_path = true)
  {
    std::fill(f_out.begin(), f_out.end(), Vec3::Zero());
    (void)vector_path; // why: read by the vector path only
    double sum_overlap = 0, worst = 0;
    long contacts = 0;
    Vec3* const f = f_out.data();
    const Vec3* const x = x_in.data();
    // One contact's contribution, in list order.
    auto add = [&](int i, int j, const Vec3& fd, double delta)
    {
      f[i] -= fd;
      f[j] += fd;
      sum_overlap += delta;
      ++contacts;
    };
    std::size_t k = 0;
#if defined(__AVX512F__)
    // Pass 1: the pairs in contact, eight pairs a step, packed in list order into the contact
    // buffers (their centre distance vectors, squared distances, radius sums and smaller radii).
    const double* X = x_in.empty() ? nullptr : x_in[0].data();
    const __m512d vs = _mm512_set1_pd(s), zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1);
    const __m256i three = _mm256_set1_epi32(3);
    const std::size_t np = vector_path ? pairs.i.size() - pairs.i.size() % 8 : 0;
    if (contact_.size() < 10 * (np + 8))
      contact_.resize(10 * (np + 8));
    double* const cx = contact_.data();
    double *const cy = cx + np + 8, *const cz = cy + np + 8, *const cd2 = cz + np + 8;
    double *const csum = cd2 + np + 8, *const cmin = csum + np + 8;
    double *const cfx = cmin + np + 8, *const cfy = cfx + np + 8, *const cfz = cfy + np + 8;
    double* const cdelta = cfz + np + 8;
    if (contact_pair_.size() < 2 * (np + 8))
      contact_pair_.resize(2 * (np + 8));
    int* const ci = contact_pair_.data();
    int* const cj = ci + np + 8;
    std::size_t nc = 0;
    for (; k < np; k += 8)
    {
      const __m256i vi = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(&pairs.i[k]));
      const __m256i vj = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(&pairs.j[k]));
      const __m256i i3 = _mm256_mullo_epi32(vi, three), j3 = _mm256_mullo_epi32(vj, three);
      const __m512d dx =
          _mm512_sub_pd(_mm512_i32gather_pd(j3, X, 8), _mm512_i32gather_pd(i3, X, 8));
      const __m512d dy =
          _mm512_sub_pd(_mm512_i32gather_pd(j3, X + 1, 8), _mm512_i32gather_pd(i3, X + 1, 8));
      const __m512d dz =
          _mm512_sub_pd(_mm512_i32gather_pd(j3, X + 2, 8), _mm512_i32gather_pd(i3, X + 2, 8));
      // (dx^2 + dy^2) + dz^2, as Eigen's squaredNorm sums
      const __m512d d2 = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)),
                                       _mm512_mul_pd(dz, dz));
      const __m512d sum = _mm512_mul_pd(vs, _mm512_loadu_pd(&pairs.radius_sum[k]));
      // contact unless d2 >= sum^2 (the scalar test, negated exactly)
      const __mmask8 touching = _mm512_cmp_pd_mask(d2, _mm512_mul_pd(sum, sum), _CMP_NGE_UQ);
      if (!touching)
        continue;
      _mm512_storeu_pd(cx + nc, _mm512_maskz_compress_pd(touching, dx));
      _mm512_storeu_pd(cy + nc, _mm512_maskz_compress_pd(touching, dy));
      _mm512_storeu_pd(cz + nc, _mm512_maskz_compress_pd(touching, dz));
      _mm512_storeu_pd(cd2 + nc, _mm512_maskz_compress_pd(touching, d2));
      _mm512_storeu_pd(csum + nc, _mm512_maskz_compress_pd(touching, sum));
      _mm512_storeu_pd(cmin + nc,
                       _mm512_maskz_compress_pd(touching, _mm512_loadu_pd(&pairs.radius_min[k])));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(ci + nc),
                          _mm256_maskz_compress_epi32(touching, vi));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(cj + nc),
                          _mm256_maskz_compress_epi32(touching, vj));
      nc += std::size_t(__builtin_popcount(touching));
    }
    // Pass 2: the contacts' terms, eight contacts a step (lanes past the last contact are
    // masked off).
    __m512d vworst = zero;
    for (std::size_t c = 0; c < nc; c += 8)
    {
      const __mmask8 live = nc - c >= 8 ? __mmask8(0xff) : __mmask8((1u << (nc - c)) - 1);
      const __m512d d2 = _mm512_maskz_loadu_pd(live, cd2 + c);
      const __m512d dist = _mm512_sqrt_pd(d2);
      const __m512d delta = _mm512_sub_pd(_mm512_maskz_loadu_pd(live, csum + c), dist);
      const __mmask8 apart = _mm512_mask_cmp_pd_mask(live, dist, zero, _CMP_GT_OQ);
      // n = d / dist, or (1, 0, 0) for coincident centres
      const __m512d nx = _mm512_mask_div_pd(one, apart, _mm512_maskz_loadu_pd(live, cx + c), dist);
      const __m512d ny = _mm512_mask_div_pd(zero, apart, _mm512_maskz_loadu_pd(live, cy + c), dist);
      const __m512d nz = _mm512_mask_div_pd(zero, apart, _mm512_maskz_loadu_pd(live, cz + c), dist);
      _mm512_storeu_pd(cfx + c, _mm512_mul_pd(delta, nx));
      _mm512_storeu_pd(cfy + c, _mm512_mul_pd(delta, ny));
      _mm512_storeu_pd(cfz + c, _mm512_mul_pd(delta, nz));
      _mm512_storeu_pd(cdelta + c, delta);
      const __m512d ratio = _mm512_maskz_div_pd(
          live, delta, _mm512_mul_pd(vs, _mm512_mask_loadu_pd(one, live, cmin + c)));
      vworst = _mm512_mask_max_pd(vworst, live, vworst, ratio); // max: exact in any order
    }
    worst = _mm512_reduce_max_pd(vworst);
    // Pass 3: the sums, one contact at a time in list order.
    for (std::size_t c = 0; c < nc; ++c)
      add(ci[c], cj[c], Vec3(cfx[c], cfy[c], cfz[c]), cdelta[c]);
#endif
    for (; k < pairs.i.size(); ++k)
    {
      const int i = pairs.i[k], j = pairs.j[k];
      const Vec3 d = x[j] - x[i];
      const double sum = s * pairs.radius_sum[k], d2 = d.squaredNorm();
      if (d2 >= sum * sum)
        continue;
      const double dist = std::sqrt(d2), delta = sum - dist;
      // why: coincident centres have no normal: separate them along x
      const Vec3 n = dist > 0 ? Vec3(d / dist) : Vec3::UnitX();
      add(i, j, Vec3(delta * n), delta);
      worst = std::max(worst, delta / (s * pairs.radius_min[k]));
    }
    return {sum_overlap, worst, contacts};
  }

private:
  std::vector<double> contact_;   // vector path: per-contact scratch (10 arrays)
  std::vector<int> contact_pair_; // vector path: the contacts' i and j
};
} // namespace dembridge::dem
