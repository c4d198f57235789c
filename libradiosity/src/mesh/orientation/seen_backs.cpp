// How much of what the scene's surfaces see are backs: the measure the orientation fixes must
// improve.
#include "radiosity/orientation.hpp"
#include "radiosity/random.hpp"
#include "radiosity/rays.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

namespace rad {

double seen_backs(const Scene& scene) {
    std::vector<std::size_t> face_of;
    std::vector<double> area;
    const auto mesh = face_triangles(scene, &face_of, &area);
    if (mesh.patches.empty()) return 0;
    const RayScene rays(mesh, RayBuild::Fast);
    constexpr int kRays = 16;
    struct Sum {
        double backs = 0, hits = 0;
    };
    const auto total = tbb::parallel_deterministic_reduce(
        tbb::blocked_range<std::size_t>(0, mesh.patches.size(), 256), Sum{},
        [&](const tbb::blocked_range<std::size_t>& range, Sum sum) {
            for (auto t = range.begin(); t != range.end(); ++t) {
                const auto& p = mesh.patches[t];
                const Vec3 n = normalized(p.normal), u = orthogonal(n), v = cross(n, u);
                const Vec3 centroid = (mesh.vertices[p.corners[0]] + mesh.vertices[p.corners[1]] +
                                       mesh.vertices[p.corners[2]]) *
                                      (1.0 / 3);
                const Vec3 from = centroid + n * (4 * rays.epsilon());
                Rng rng(0x6261636b, t);
                for (int k = 0; k < kRays; ++k) {
                    bool front = false;
                    if (rays.first_hit(from,
                                       cosine_direction(n, u, v, rng.uniform(), rng.uniform()),
                                       front) < 0)
                        continue;
                    sum.hits += area[t];
                    if (!front) sum.backs += area[t];
                }
            }
            return sum;
        },
        [](Sum a, const Sum& b) {
            a.backs += b.backs;
            a.hits += b.hits;
            return a;
        });
    return total.hits > 0 ? total.backs / total.hits : 0;
}

} // namespace rad
