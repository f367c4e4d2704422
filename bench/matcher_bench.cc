// The descriptor matcher's time per image pair at 2k, 4k and 8k SIFT features, beside the floor
// that its matrix product sets (the BLAS's SGEMM of the same size alone), on one thread and with
// pairs spread over the machine's threads as MatchImagePairs runs them.
//
//   ramap_bench_matcher [--threads N] [--pairs P]
//
// Descriptors are the synthetic SIFT-like ones (synthetic/synthetic_descriptors.h): half of the
// second image's rows are noisy views of the first image's, as in a well-overlapping pair. The
// time does not depend on their content.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "ramap/features/descriptor_matching.h"
#include "ramap/synthetic/synthetic_descriptors.h"
#include "ramap/util/blas_threads.h"
#include "ramap/util/cblas.h"
#include "ramap/util/parallel.h"

namespace {

using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

// Two images' descriptors of `count` rows each: a synthetic pair of views that share points.
std::pair<ramap::Descriptors, ramap::Descriptors> PairDescriptors(int count) {
  ramap::SyntheticSceneOptions options;
  options.layout = ramap::SyntheticLayout::kUnordered;
  options.num_images = 2;
  options.num_points = 3 * count;
  options.camera_distance = 6.0;
  ramap::SyntheticScene scene = ramap::BuildSyntheticScene(options);
  ramap::AddSyntheticDescriptors(ramap::SyntheticDescriptorOptions(), &scene);
  auto take = [&](uint32_t id) {
    ramap::Descriptors d = scene.database.descriptors.at(id);
    // Repeat rows when the views saw fewer keypoints than asked for.
    const size_t have = d.size();
    while (d.size() < static_cast<size_t>(count)) {
      d.data.insert(d.data.end(), d.data.begin(),
                    d.data.begin() + std::min(have, count - d.size()) * d.num_cols);
    }
    d.data.resize(static_cast<size_t>(count) * d.num_cols);
    return d;
  };
  return {take(1), take(2)};
}

}  // namespace

int main(int argc, char** argv) {
  int threads = 2, pairs = 8;
  for (int k = 1; k + 1 < argc; k += 2) {
    if (!std::strcmp(argv[k], "--threads")) threads = std::stoi(argv[k + 1]);
    if (!std::strcmp(argv[k], "--pairs")) pairs = std::stoi(argv[k + 1]);
  }
  std::printf(
      "| features | SGEMM alone, 1 thread (ms) | SGEMM GFLOP/s | matcher, 1 thread (ms per pair) | "
      "matcher / SGEMM | matcher, %d threads (ms per pair) | matches |\n",
      threads);
  std::printf("| --- | --- | --- | --- | --- | --- | --- |\n");
  for (const int count : {2000, 4000, 8000}) {
    const auto [one, two] = PairDescriptors(count);
    std::vector<float> a(one.data.begin(), one.data.end()), b(two.data.begin(), two.data.end());
    std::vector<float> products(512 * static_cast<size_t>(count));
    ramap::SingleBlasThread single_blas_thread;
    auto start = Clock::now();
    for (int p = 0; p < pairs; ++p) {
      for (int begin = 0; begin < count; begin += 512) {
        cblas_sgemm(CblasRowMajor, CblasNoTrans, CblasTrans, std::min(512, count - begin), count,
                    128, 1.0f, &a[static_cast<size_t>(begin) * 128], 128, b.data(), 128, 0.0f,
                    products.data(), count);
      }
    }
    const double gemm = Seconds(start) / pairs;
    size_t num_matches = 0;
    start = Clock::now();
    for (int p = 0; p < pairs; ++p) {
      num_matches = ramap::MatchDescriptors(one, two, ramap::DescriptorMatchingOptions()).size();
    }
    const double serial = Seconds(start) / pairs;
    start = Clock::now();
    ramap::ParallelFor(pairs * threads, threads, [&, &one = one, &two = two](size_t) {
      ramap::MatchDescriptors(one, two, ramap::DescriptorMatchingOptions());
    });
    const double parallel = Seconds(start) / (pairs * threads);
    const double flops = 2.0 * count * count * 128;
    std::printf("| %d | %.1f | %.0f | %.1f | %.2f | %.1f | %zu |\n", count, 1e3 * gemm,
                flops / gemm / 1e9, 1e3 * serial, serial / gemm, 1e3 * parallel, num_matches);
  }
  return 0;
}
