// Solvers as plugins over a transport operator: one file per solver under src/solver/ and
// one line in src/solver/registry.cpp.
#pragma once
#include "radiosity/transport.hpp"

#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rad {

struct IterationRecord {
    long iteration = 0;        // sweeps for sweep solvers, shots for shooting solvers
    double residual = 0;       // relative change per sweep, or the unshot power fraction
    std::vector<double> power; // sum_i B_i A_i of the displayed solution, per channel
    double seconds = 0;
};

struct SolveControl {
    long max_iterations = 0; // 0: no limit besides the tolerance
    double tolerance = 0;    // 0: run max_iterations exactly
    // Called after every iteration. `displayed` makes the displayed state (APR includes its
    // ambient term) when called: for a shooting solver that is O(patches) a shot, so only
    // when it is needed (a snapshot), not for the record's power, which is kept up to date.
    std::function<void(const IterationRecord&, const std::function<Channels()>& displayed)>
        on_iteration;
};

struct SolveResult {
    Channels radiosity; // what to display: APR includes the ambient term
    long iterations = 0;
    double residual = 0;
    bool converged = false;
};

class Solver {
  public:
    virtual ~Solver() = default;
    virtual std::string_view name() const = 0;
    virtual std::string_view summary() const = 0; // one line for --help
    // Shooting solvers count shots as iterations (so --sweeps applies); sweep solvers count
    // sweeps over all patches.
    virtual bool shooting() const = 0;
    // The header field the final residual is recorded under.
    std::string_view residual_name() const { return shooting() ? "unshot_fraction" : "residual"; }
    // Iterations when the user sets none: enough to converge on any sane scene.
    virtual long default_max_iterations(std::size_t patches) const = 0;
    virtual SolveResult solve(const TransportOperator& op, const Channels& emission,
                              const SolveControl& control) const = 0;
};

std::span<const Solver* const> solvers();
std::vector<std::string> solver_names();
// Throws InputError naming the known solvers when `name` is not one of them.
const Solver& solver(std::string_view name);

} // namespace rad
