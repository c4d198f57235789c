// rad-solve: furnace, agreement with a direct dense solve, convergence behaviour, APR.
#include "helpers.hpp"
#include "radiosity/error.hpp"
#include "radiosity/formfactor.hpp"
#include "radiosity/progress.hpp"
#include "radiosity/solve_policy.hpp"
#include "radiosity/solver.hpp"

#include <catch2/catch.hpp>

using namespace testing_helpers;
using radfmt::Rgb;

namespace {

const std::vector<std::string> kAll = rad::solver_names();

// An operator over its own form factors, with per-patch RGB reflectance and emission.
struct Problem {
    radfmt::FormFactorData ff;
    std::vector<double> area;
    std::vector<Rgb> reflectance, emission;

    rad::TransportOperator op() const {
        rad::TransportOperator o;
        o.form_factors = &ff;
        o.area = area;
        for (const auto& r : reflectance)
            for (double x : r) o.reflectance.push_back(x);
        return o;
    }
};

radfmt::FormFactorData analytic(const radfmt::MeshData& mesh) {
    rad::FormFactorOptions options;
    options.quiet = true;
    return rad::compute_form_factors(mesh, options);
}

std::vector<std::vector<double>> dense(const radfmt::FormFactorData& ff) {
    std::vector<std::vector<double>> f(ff.patch_count, std::vector<double>(ff.patch_count, 0));
    for (std::size_t i = 0; i < ff.patch_count; ++i)
        for (auto k = ff.row_start[i]; k < ff.row_start[i + 1]; ++k)
            f[i][ff.columns[k]] = ff.values[k];
    return f;
}

radfmt::FormFactorData sparse(const std::vector<std::vector<double>>& f) {
    radfmt::FormFactorData ff;
    ff.patch_count = f.size();
    ff.row_start.push_back(0);
    for (const auto& row : f) {
        for (std::size_t j = 0; j < row.size(); ++j)
            if (row[j] != 0) {
                ff.columns.push_back(static_cast<std::uint32_t>(j));
                ff.values.push_back(static_cast<float>(row[j]));
            }
        ff.row_start.push_back(ff.columns.size());
    }
    return ff;
}

// Makes A_i F_ij = A_j F_ji exact, as progressive refinement assumes.
std::vector<std::vector<double>> reciprocal(const std::vector<std::vector<double>>& f,
                                            const std::vector<double>& area) {
    auto g = f;
    for (std::size_t i = 0; i < f.size(); ++i)
        for (std::size_t j = 0; j < f.size(); ++j)
            g[i][j] = 0.5 * (area[i] * f[i][j] + area[j] * f[j][i]) / area[i];
    return g;
}

// Direct solve of (I - diag(rho) F) B = E by Gaussian elimination with partial pivoting.
std::vector<Rgb> dense_solve(const Problem& p) {
    const auto f = dense(p.ff);
    const std::size_t n = f.size();
    std::vector<Rgb> b(n);
    for (int c = 0; c < 3; ++c) {
        std::vector<std::vector<double>> m(n, std::vector<double>(n + 1));
        for (std::size_t i = 0; i < n; ++i) {
            for (std::size_t j = 0; j < n; ++j) m[i][j] = (i == j) - p.reflectance[i][c] * f[i][j];
            m[i][n] = p.emission[i][c];
        }
        for (std::size_t col = 0; col < n; ++col) {
            std::size_t pivot = col;
            for (std::size_t r = col + 1; r < n; ++r)
                if (std::abs(m[r][col]) > std::abs(m[pivot][col])) pivot = r;
            std::swap(m[col], m[pivot]);
            for (std::size_t r = 0; r < n; ++r) {
                if (r == col) continue;
                const double factor = m[r][col] / m[col][col];
                for (std::size_t k = col; k <= n; ++k) m[r][k] -= factor * m[col][k];
            }
        }
        for (std::size_t i = 0; i < n; ++i) b[i][c] = m[i][n] / m[i][i];
    }
    return b;
}

rad::SolveResult run(const Problem& p, const std::string& method, double tolerance,
                     long iterations = 0, std::vector<rad::IterationRecord>* log = nullptr) {
    rad::SolveControl control;
    control.tolerance = tolerance;
    control.max_iterations = iterations ? iterations : 10000000;
    if (log)
        control.on_iteration = [&](const rad::IterationRecord& r,
                                   const std::function<rad::Channels()>&) { log->push_back(r); };
    return rad::solver(method).solve(p.op(), rad::to_channels(p.emission), control);
}

// A closed cube with a floating two-sided block inside (occlusion), light on part of the top.
radfmt::MeshData occluded_scene() {
    return mesh_from_obj(cube_obj() + "v 0.3 0.3 0.4\nv 0.7 0.3 0.4\nv 0.7 0.7 0.4\nv 0.3 0.7 0.4\n"
                                      "g block\nf 9 10 11 12\nf 9 12 11 10\n",
                         0.34);
}

} // namespace

TEST_CASE(
    "furnace: a closed cube with uniform rho and E gives B = E / (1 - rho) for every method") {
    const auto mesh = mesh_from_obj(cube_obj(), 0.25);
    auto f = dense(analytic(mesh));
    // Equal areas: a symmetric matrix is reciprocal. Sinkhorn balancing then makes every row
    // (and column) sum to exactly one, the closed scene's exact property.
    f = reciprocal(f, std::vector<double>(f.size(), 1.0));
    for (int round = 0; round < 200; ++round) {
        std::vector<double> scale(f.size());
        for (std::size_t i = 0; i < f.size(); ++i) {
            double sum = 0;
            for (double x : f[i]) sum += x;
            scale[i] = 1 / std::sqrt(sum);
        }
        for (std::size_t i = 0; i < f.size(); ++i)
            for (std::size_t j = 0; j < f.size(); ++j) f[i][j] *= scale[i] * scale[j];
    }
    Problem p;
    p.ff = sparse(f);
    const Rgb rho{0.5, 0.8, 0.2}, e{1, 2, 3};
    for (const auto& patch : mesh.patches) {
        p.area.push_back(patch.area);
        p.reflectance.push_back(rho);
        p.emission.push_back(e);
    }
    for (const auto& method : kAll) {
        const auto result = run(p, method, 1e-12);
        CAPTURE(method);
        for (const auto& b : rad::to_rgb(result.radiosity))
            for (int c = 0; c < 3; ++c) CHECK(b[c] == Approx(e[c] / (1 - rho[c])).epsilon(1e-6));
    }
}

TEST_CASE("every method agrees with a direct dense solve on an occluded scene") {
    const auto mesh = occluded_scene();
    std::vector<double> area;
    for (const auto& patch : mesh.patches) area.push_back(patch.area);
    Problem p;
    p.ff = sparse(reciprocal(dense(analytic(mesh)), area));
    for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
        const auto& patch = mesh.patches[i];
        p.area.push_back(patch.area);
        const bool lamp = patch.group == 1 && patch.centroid[0] < 0.5; // part of the top
        p.reflectance.push_back(patch.group == 6 ? Rgb{0.7, 0.3, 0.1} : Rgb{0.6, 0.6, 0.6});
        p.emission.push_back(lamp ? Rgb{5, 4, 3} : Rgb{0, 0, 0});
    }
    const auto exact = dense_solve(p);
    double scale = 0;
    for (const auto& b : exact) scale = std::max({scale, b[0], b[1], b[2]});
    for (const auto& method : kAll) {
        const auto result = run(p, method, 1e-13);
        CAPTURE(method);
        for (std::size_t i = 0; i < exact.size(); ++i)
            for (int c = 0; c < 3; ++c)
                CHECK(std::abs(result.radiosity.at(i, c) - exact[i][c]) < 1e-6 * scale);
    }
    CHECK(run(p, "gs", 1e-8).iterations < run(p, "jacobi", 1e-8).iterations);

    SECTION("Gauss-Seidel brightens monotonically from B = E") {
        std::vector<rad::IterationRecord> log;
        run(p, "gs", 0, 10, &log);
        REQUIRE(log.size() == 10);
        for (std::size_t k = 1; k < log.size(); ++k)
            for (int c = 0; c < 3; ++c) CHECK(log[k].power[c] >= log[k - 1].power[c]);
        CHECK(log[3].power[0] > log[0].power[0]); // iteration 4 is brighter than iteration 1
    }
    SECTION("a shot's logged power, kept up to date, is the displayed state's power") {
        for (const char* method : {"pr", "apr"}) {
            for (long shots : {1L, 7L, 200L}) {
                std::vector<rad::IterationRecord> log;
                const auto result = run(p, method, 0, shots, &log);
                REQUIRE(log.size() == std::size_t(shots));
                const auto power = rad::total_power(p.op().area, result.radiosity);
                CAPTURE(method, shots);
                for (int c = 0; c < 3; ++c)
                    CHECK(log.back().power[c] == Approx(power[c]).epsilon(1e-12));
            }
        }
    }
    SECTION(
        "APR's first shot lights every patch; PR's leaves some black; the ambient term decays") {
        const auto apr = run(p, "apr", 0, 1);
        const auto pr = run(p, "pr", 0, 1);
        std::size_t pr_black = 0;
        for (std::size_t i = 0; i < apr.radiosity.patches(); ++i) {
            CHECK(apr.radiosity.at(i, 0) > 0);
            pr_black += pr.radiosity.at(i, 0) == 0;
        }
        CHECK(pr_black > 0);
        auto ambient_gap = [&](long shots) {
            const auto a = run(p, "apr", 0, shots);
            const auto b = run(p, "pr", 0, shots);
            double gap = 0;
            for (std::size_t i = 0; i < a.radiosity.patches(); ++i)
                gap += a.radiosity.at(i, 0) - b.radiosity.at(i, 0);
            return gap;
        };
        CHECK(ambient_gap(100) < ambient_gap(10));
        CHECK(ambient_gap(10) < ambient_gap(1));
    }
}

// The occluded scene's operator, its block (group 6) coloured: for right-hand sides of any
// number of channels (no emission of its own).
Problem coloured_occluded_problem(const radfmt::MeshData& mesh) {
    Problem p;
    for (const auto& patch : mesh.patches) {
        p.area.push_back(patch.area);
        p.reflectance.push_back(patch.group == 6 ? Rgb{0.7, 0.3, 0.1} : Rgb{0.6, 0.5, 0.4});
    }
    p.ff = sparse(reciprocal(dense(analytic(mesh)), p.area));
    return p;
}

TEST_CASE("right-hand sides with any number of channels: each channel solves on its own") {
    // Two RGB light groups stacked as 6 channels (channel c reflects with colour c % 3) give,
    // channel by channel, the same numbers as two separate RGB solves.
    const auto mesh = occluded_scene();
    const auto p = coloured_occluded_problem(mesh);
    const std::size_t n = mesh.patches.size();
    rad::Channels a(n, 3), b(n, 3), both(n, 6);
    for (std::size_t i = 0; i < n; ++i) {
        const bool top = mesh.patches[i].group == 1, bottom = mesh.patches[i].group == 0;
        for (int c = 0; c < 3; ++c) {
            a.at(i, c) = top ? 5.0 + c : 0;
            b.at(i, c) = bottom ? 1.0 + 2 * c : 0;
            both.at(i, c) = a.at(i, c);
            both.at(i, 3 + c) = b.at(i, c);
        }
    }
    for (const auto& method : kAll) {
        CAPTURE(method);
        rad::SolveControl control;
        control.tolerance = 1e-12;
        control.max_iterations = 10000000;
        const auto& solver = rad::solver(method);
        const auto ra = solver.solve(p.op(), a, control);
        const auto rb = solver.solve(p.op(), b, control);
        const auto rboth = solver.solve(p.op(), both, control);
        REQUIRE(rboth.radiosity.channels == 6);
        double scale = 0;
        for (double v : rboth.radiosity.values) scale = std::max(scale, v);
        for (std::size_t i = 0; i < n; ++i)
            for (int c = 0; c < 3; ++c) {
                CHECK(std::abs(rboth.radiosity.at(i, c) - ra.radiosity.at(i, c)) < 1e-6 * scale);
                CHECK(std::abs(rboth.radiosity.at(i, 3 + c) - rb.radiosity.at(i, c)) <
                      1e-6 * scale);
            }
    }
}

TEST_CASE("many channels (a sky's light groups) solve in parallel blocks, each channel as on its "
          "own, the same bytes at any thread count") {
    // 50 RGB groups (150 channels: blocks of 48, the last of 6), each lit from one patch.
    const auto mesh = occluded_scene();
    const auto p = coloured_occluded_problem(mesh);
    const std::size_t n = mesh.patches.size(), groups = 50;
    rad::Channels all(n, 3 * groups);
    for (std::size_t g = 0; g < groups; ++g)
        for (int c = 0; c < 3; ++c) all.at((g * 7) % n, 3 * g + c) = 1.0 + g + c;
    rad::SolveControl control;
    control.tolerance = 1e-12;
    control.max_iterations = 100000;
    for (const char* method : {"gs", "jacobi"}) {
        CAPTURE(method);
        const auto& solver = rad::solver(method);
        rad::SolveResult one, two;
        {
            rad::ThreadLimit limit(1);
            one = solver.solve(p.op(), all, control);
        }
        {
            rad::ThreadLimit limit(2);
            two = solver.solve(p.op(), all, control);
        }
        CHECK(one.radiosity.values == two.radiosity.values);
        CHECK(one.iterations == two.iterations);
        for (std::size_t g = 0; g < groups; g += 7) { // against the group solved alone (RGB)
            rad::Channels alone(n, 3);
            for (std::size_t i = 0; i < n; ++i)
                for (int c = 0; c < 3; ++c) alone.at(i, c) = all.at(i, 3 * g + c);
            const auto single = solver.solve(p.op(), alone, control);
            for (std::size_t i = 0; i < n; ++i)
                for (int c = 0; c < 3; ++c)
                    CHECK(one.radiosity.at(i, 3 * g + c) ==
                          Approx(single.radiosity.at(i, c)).epsilon(1e-9).margin(1e-12));
        }
    }
}

TEST_CASE("the solver registry lists every solver and names them in errors") {
    CHECK(rad::solver_names() == std::vector<std::string>{"gs", "jacobi", "pr", "apr"});
    CHECK(rad::solver("pr").shooting());
    CHECK_FALSE(rad::solver("gs").shooting());
    CHECK(rad::solver("apr").residual_name() == "unshot_fraction");
    CHECK_THROWS_AS(rad::solver("sor"), rad::InputError);
    CHECK_THROWS_WITH(rad::solver("sor"), Catch::Contains("use gs, jacobi, pr, apr"));
}

TEST_CASE(
    "progressive refinement shoots in the order of a full scan (heap = argmax, lowest index)") {
    // The reference: the patch with the most unshot power, found by scanning every patch,
    // the first of equals (what PR did before its heap). Same shots, same order: the same
    // radiosity, bit for bit.
    const auto mesh = cornell_mesh(0.1);
    const auto ff = analytic(mesh);
    const auto op = rad::make_operator(mesh, ff);
    const auto emission = rad::emission_of(mesh);
    const std::size_t n = op.patch_count();
    const long shots = static_cast<long>(3 * n);
    rad::Channels b = emission, unshot = emission;
    for (long s = 0; s < shots; ++s) {
        std::size_t shooter = 0;
        double best = -1;
        for (std::size_t i = 0; i < n; ++i) {
            double u = 0;
            for (std::size_t c = 0; c < 3; ++c) u += unshot.at(i, c);
            if (u * op.area[i] > best) best = u * op.area[i], shooter = i;
        }
        if (best <= 0) break;
        double shot[3];
        for (std::size_t c = 0; c < 3; ++c)
            shot[c] = unshot.at(shooter, c), unshot.at(shooter, c) = 0;
        for (auto k = ff.row_start[shooter]; k < ff.row_start[shooter + 1]; ++k) {
            const auto j = ff.columns[k];
            const double f_ji = ff.values[k] * op.area[shooter] / op.area[j];
            for (std::size_t c = 0; c < 3; ++c) {
                const double received = op.rho(j, c) * shot[c] * f_ji;
                b.at(j, c) += received;
                unshot.at(j, c) += received;
            }
        }
    }
    rad::SolveControl control;
    control.max_iterations = shots;
    const auto result = rad::solver("pr").solve(op, emission, control);
    CHECK(result.iterations == shots);
    CHECK(result.radiosity.values == b.values);
}

TEST_CASE("a matrix kept as its compact rows solves bit for bit as its plain arrays") {
    // rad-solve keeps a hemisphere matrix's rows packed and decodes them as it reads them;
    // every solver, RGB and stacked light groups, must give exactly what the arrays give.
    const auto mesh = cornell_mesh(0.1);
    rad::FormFactorOptions options;
    options.quiet = true;
    options.method = "hemisphere";
    options.rays = 500;
    const auto computed = rad::compute_form_factors(mesh, options);
    const auto dir = temp_dir("compact-solve");
    radfmt::Header header;
    header.tool = "test";
    for (const auto& [key, value] : rad::form_factor_header_fields(options)) header.set(key, value);
    radfmt::write_form_factors(dir / "c.ff", header, computed);
    const auto plain = radfmt::read_form_factors(dir / "c.ff");
    const auto compact =
        radfmt::read_form_factors(dir / "c.ff", nullptr, radfmt::FormFactorLayout::compact);
    REQUIRE(compact.is_compact());
    REQUIRE(compact.columns.empty());
    REQUIRE(compact.nonzeros() == plain.nonzeros());
    CHECK(rad::check_row_sums(compact, 0).largest == rad::check_row_sums(plain, 0).largest);
    const auto emission = rad::emission_of(mesh);
    rad::Channels stacked(emission.patches(), 6);
    for (std::size_t i = 0; i < emission.patches(); ++i)
        for (std::size_t c = 0; c < 6; ++c)
            stacked.at(i, c) = c < 3 ? emission.at(i, c) : 0.25 * (i % 3 == 0);
    for (const auto& method : kAll) {
        CAPTURE(method);
        rad::SolveControl control;
        control.max_iterations = rad::solver(method).shooting() ? 3 * long(mesh.patches.size()) : 8;
        for (const rad::Channels* e : {&emission, static_cast<const rad::Channels*>(&stacked)}) {
            const auto a = rad::solver(method).solve(rad::make_operator(mesh, plain), *e, control);
            const auto b =
                rad::solver(method).solve(rad::make_operator(mesh, compact), *e, control);
            CHECK(a.radiosity.values == b.radiosity.values);
        }
    }
}
