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
#include "dem/core/simd_gather.h"
#include "dem/core/types.h"
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>
#if defined(__AVX512F__)
#include <immintrin.h>
#endif
#if defined(_OPENMP)
#include <omp.h>
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
  /// f_out = the overlap forces of the pairs at radius scale s (f_out sized like x_in). The
  /// vector path runs on `threads` threads with the one-thread result: the pairs are split into
  /// consecutive chunks whose contacts are packed and evaluated in parallel, and each thread then
  /// adds, for the spheres it owns, the contacts' terms in list order. The vector path skips
  /// the overlap sum unless `need_sum` and the largest ratio unless `need_worst` (then NaN).
  OverlapSums compute(const OverlapPairs& pairs, const std::vector<Vec3>& x_in, double s,
                      std::vector<Vec3>& f_out, bool vector_path = true, int threads = 1,
                      bool need_sum = true, bool need_worst = true)
  {
    (void)vector_path; // why: read by the vector path only
    (void)threads;
    (void)need_sum;
    (void)need_worst;
#if !defined(_OPENMP)
    threads = 1;
#endif
    double sum_overlap = 0, worst = 0;
    long contacts = 0;
    Vec3* const f = f_out.data();
    const Vec3* const x = x_in.data();
    std::size_t k = 0;
#if defined(__AVX512F__)
    const std::size_t np = vector_path ? pairs.i.size() - pairs.i.size() % 8 : 0;
    if (np > 0)
    {
      const int nt = int(std::clamp<std::size_t>(std::size_t(std::max(threads, 1)), 1, np / 8));
      const std::size_t stride = np + 8 * std::size_t(nt); // each chunk's region has 8 spare
      if (contact_.size() < 10 * stride)
        contact_.resize(10 * stride);
      if (contact_pair_.size() < 2 * stride)
        contact_pair_.resize(2 * stride);
      chunk_count_.assign(std::size_t(nt), 0);
      export_count_.assign(std::size_t(nt), 0);
      exports_.resize(std::size_t(nt));
      chunk_worst_.assign(std::size_t(nt), 0.0);
      const std::size_t nx = x_in.size();
      // Chunk c holds the pairs [chunk_begin(c), chunk_begin(c + 1)), multiples of 8; its
      // contacts start at slot_base(c) of each scratch array (8 spare slots a chunk).
      const auto chunk_begin = [&](int c) { return np / 8 * std::size_t(c) / std::size_t(nt) * 8; };
      const auto slot_base = [&](int c) { return chunk_begin(c) + 8 * std::size_t(c); };
#pragma omp parallel num_threads(nt)
      {
#if defined(_OPENMP)
        const int t = omp_get_thread_num();
#else
        const int t = 0;
#endif
        const std::size_t b = chunk_begin(t), e = chunk_begin(t + 1), base = slot_base(t);
        std::fill(f + nx * std::size_t(t) / std::size_t(nt),
                  f + nx * std::size_t(t + 1) / std::size_t(nt), Vec3::Zero());
        chunk_count_[std::size_t(t)] = pack_contacts(pairs, x_in, s, b, e, contact_.data() + base,
                                                     stride, contact_pair_.data() + base, stride);
        const std::size_t nc_own = chunk_count_[std::size_t(t)];
        chunk_worst_[std::size_t(t)] =
            contact_terms(s, nc_own, contact_.data() + base, stride, need_worst);
        // Sphere i belongs to thread t if lo <= i < hi. The contacts of this chunk that touch a
        // sphere of another thread are listed for it (branch-free append).
        const int lo = int(nx * std::size_t(t) / std::size_t(nt));
        const int hi = int(nx * std::size_t(t + 1) / std::size_t(nt));
        if (nt > 1)
        {
          const int* const ci = contact_pair_.data() + base;
          const int* const cj = ci + stride;
          std::vector<int>& ex = exports_[std::size_t(t)];
          if (ex.size() < nc_own)
            ex.resize(nc_own);
          std::size_t ne = 0;
          for (std::size_t q = 0; q < nc_own; ++q)
          {
            ex[ne] = int(q);
            ne += std::size_t((ci[q] < lo) | (ci[q] >= hi) | (cj[q] < lo) | (cj[q] >= hi));
          }
          export_count_[std::size_t(t)] = ne;
        }
#pragma omp barrier
        // The sums: each thread adds, chunk after chunk in list order, the terms of the spheres
        // it owns (from its own chunk all contacts, from the others their exported ones), so
        // each sphere gets its terms in the one-thread order. Thread 0 also sums the overlaps
        // in list order (in the loop over its own chunk, then over the others' deltas).
        const bool sums_here = need_sum && t == 0;
        double overlap_sum = 0;
        for (int c = 0; c < nt; ++c)
        {
          const std::size_t cb = slot_base(c);
          const double* const cfx = contact_.data() + 6 * stride + cb;
          const double* const cfy = cfx + stride;
          const double* const cfz = cfy + stride;
          const double* const cdelta = cfz + stride;
          const int* const ci = contact_pair_.data() + cb;
          const int* const cj = ci + stride;
          auto add = [&](std::size_t q)
          {
            const Vec3 fd(cfx[q], cfy[q], cfz[q]);
            if (ci[q] >= lo && ci[q] < hi)
              f[ci[q]] -= fd;
            if (cj[q] >= lo && cj[q] < hi)
              f[cj[q]] += fd;
          };
          if (c == t && sums_here)
            for (std::size_t q = 0; q < nc_own; ++q)
            {
              add(q);
              overlap_sum += cdelta[q];
            }
          else if (c == t)
            for (std::size_t q = 0; q < nc_own; ++q)
              add(q);
          else
          {
            const int* const ex = exports_[std::size_t(c)].data();
            for (std::size_t e = 0; e < export_count_[std::size_t(c)]; ++e)
              add(std::size_t(ex[e]));
            if (sums_here)
              for (std::size_t q = 0; q < chunk_count_[std::size_t(c)]; ++q)
                overlap_sum += cdelta[q];
          }
        }
        if (sums_here)
          sum_overlap = overlap_sum;
      }
      for (int t = 0; t < nt; ++t)
      {
        contacts += long(chunk_count_[std::size_t(t)]);
        worst = std::max(worst, chunk_worst_[std::size_t(t)]); // max: exact in any order
      }
      k = np;
      if (!need_sum)
        sum_overlap = std::numeric_limits<double>::quiet_NaN();
      if (!need_worst)
        worst = std::numeric_limits<double>::quiet_NaN();
    }
    else
      std::fill(f_out.begin(), f_out.end(), Vec3::Zero());
#else
    std::fill(f_out.begin(), f_out.end(), Vec3::Zero());
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
      f[i] -= delta * n;
      f[j] += delta * n;
      sum_overlap += delta;
      ++contacts;
      worst = std::max(worst, delta / (s * pairs.radius_min[k]));
    }
    return {sum_overlap, worst, contacts};
  }

private:
  std::vector<double> contact_;          // vector path: per-contact scratch (10 arrays of `stride`)
  std::vector<int> contact_pair_;        // vector path: the contacts' i and j (2 arrays)
  std::vector<std::size_t> chunk_count_; // contacts of each thread's chunk
  std::vector<double> chunk_worst_;      // largest overlap ratio of each chunk
  std::vector<std::vector<int>> exports_; // each chunk's contacts touching other threads' spheres
  std::vector<std::size_t> export_count_;

#if defined(__AVX512F__)
  /// Pass 1: the pairs [b, e) in contact, eight pairs a step, packed in list order into the
  /// contact arrays at c (x, y, z of the distance vector, squared distance, radius sum, smaller
  /// radius; `stride` apart) and cij (i, j); returns their count.
  static std::size_t pack_contacts(const OverlapPairs& pairs, const std::vector<Vec3>& x_in,
                                   double s, std::size_t b, std::size_t e, double* c,
                                   std::size_t stride, int* cij, std::size_t pair_stride)
  {
    const double* X = x_in[0].data();
    const __m512d vs = _mm512_set1_pd(s);
    double *const cx = c, *const cy = cx + stride, *const cz = cy + stride;
    double *const cd2 = cz + stride, *const csum = cd2 + stride, *const cmin = csum + stride;
    int *const ci = cij, *const cj = cij + pair_stride;
    // why: the stores below may alias the vectors' own pointers for all the compiler knows, so
    // it would reload them every step
    const int *const pi = pairs.i.data(), *const pj = pairs.j.data();
    const double* const radius_sum = pairs.radius_sum.data();
    const double* const radius_min = pairs.radius_min.data();
    std::size_t nc = 0;
    for (std::size_t k = b; k < e; k += 8)
    {
      const __m256i vi = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(pi + k));
      const __m256i vj = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(pj + k));
      // x_i and x_j of the eight pairs as rows x, y, z (and a spare)
      alignas(64) double xi[4][8], xj[4][8];
      gather_rows<8, 3>(X, pi + k, xi);
      gather_rows<8, 3>(X, pj + k, xj);
      const __m512d dx = _mm512_sub_pd(_mm512_load_pd(xj[0]), _mm512_load_pd(xi[0]));
      const __m512d dy = _mm512_sub_pd(_mm512_load_pd(xj[1]), _mm512_load_pd(xi[1]));
      const __m512d dz = _mm512_sub_pd(_mm512_load_pd(xj[2]), _mm512_load_pd(xi[2]));
      // (dx^2 + dy^2) + dz^2, as Eigen's squaredNorm sums
      const __m512d d2 = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)),
                                       _mm512_mul_pd(dz, dz));
      const __m512d sum = _mm512_mul_pd(vs, _mm512_loadu_pd(radius_sum + k));
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
                       _mm512_maskz_compress_pd(touching, _mm512_loadu_pd(radius_min + k)));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(ci + nc),
                          _mm256_maskz_compress_epi32(touching, vi));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(cj + nc),
                          _mm256_maskz_compress_epi32(touching, vj));
      nc += std::size_t(__builtin_popcount(touching));
    }
    return nc;
  }

  /// Pass 2: the nc contacts' terms at c (pack_contacts' layout), eight contacts a step (lanes
  /// past the last contact masked off): delta n into the arrays 6-8, delta into 9; returns the
  /// largest delta / (s min(R_i, R_j)) if need_worst (else 0).
  static double contact_terms(double s, std::size_t nc, double* c, std::size_t stride,
                              bool need_worst)
  {
    const __m512d vs = _mm512_set1_pd(s), zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1);
    const double *const cx = c, *const cy = cx + stride, *const cz = cy + stride;
    const double *const cd2 = cz + stride, *const csum = cd2 + stride, *const cmin = csum + stride;
    double *const cfx = c + 6 * stride, *const cfy = cfx + stride, *const cfz = cfy + stride;
    double* const cdelta = cfz + stride;
    __m512d vworst = zero;
    for (std::size_t q = 0; q < nc; q += 8)
    {
      const __mmask8 live = nc - q >= 8 ? __mmask8(0xff) : __mmask8((1u << (nc - q)) - 1);
      const __m512d d2 = _mm512_maskz_loadu_pd(live, cd2 + q);
      const __m512d dist = _mm512_sqrt_pd(d2);
      const __m512d delta = _mm512_sub_pd(_mm512_maskz_loadu_pd(live, csum + q), dist);
      const __mmask8 apart = _mm512_mask_cmp_pd_mask(live, dist, zero, _CMP_GT_OQ);
      // n = d / dist, or (1, 0, 0) for coincident centres
      const __m512d nx = _mm512_mask_div_pd(one, apart, _mm512_maskz_loadu_pd(live, cx + q), dist);
      const __m512d ny = _mm512_mask_div_pd(zero, apart, _mm512_maskz_loadu_pd(live, cy + q), dist);
      const __m512d nz = _mm512_mask_div_pd(zero, apart, _mm512_maskz_loadu_pd(live, cz + q), dist);
      _mm512_storeu_pd(cfx + q, _mm512_mul_pd(delta, nx));
      _mm512_storeu_pd(cfy + q, _mm512_mul_pd(delta, ny));
      _mm512_storeu_pd(cfz + q, _mm512_mul_pd(delta, nz));
      _mm512_storeu_pd(cdelta + q, delta);
      if (!need_worst)
        continue;
      const __m512d ratio = _mm512_maskz_div_pd(
          live, delta, _mm512_mul_pd(vs, _mm512_mask_loadu_pd(one, live, cmin + q)));
      vworst = _mm512_mask_max_pd(vworst, live, vworst, ratio); // max: exact in any order
    }
    return _mm512_reduce_max_pd(vworst);
  }
#endif
};
} // namespace dembridge::dem
