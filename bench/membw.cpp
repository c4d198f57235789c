// Measured memory bandwidth, the limit a Gauss-Seidel sweep is compared against: one thread
// (a GS sweep is sequential) streaming through a buffer much larger than the caches.
//   bench-membw [MiB]   -> prints "read_bytes_per_second B"
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

int main(int argc, char** argv) {
    const std::size_t mib = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 1024;
    std::vector<double> data(mib * 1024 * 1024 / sizeof(double), 1.0);
    double best = 0, sink = 0;
    for (int round = 0; round < 5; ++round) {
        const auto start = std::chrono::steady_clock::now();
        double sum0 = 0, sum1 = 0, sum2 = 0, sum3 = 0;
        for (std::size_t i = 0; i + 3 < data.size(); i += 4) {
            sum0 += data[i];
            sum1 += data[i + 1];
            sum2 += data[i + 2];
            sum3 += data[i + 3];
        }
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        sink += sum0 + sum1 + sum2 + sum3;
        best = std::max(best, data.size() * sizeof(double) / seconds);
    }
    std::printf("read_bytes_per_second %.6g (checksum %.0f)\n", best, sink);
    return 0;
}
