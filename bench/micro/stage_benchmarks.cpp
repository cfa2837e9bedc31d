// tm-bench-stages: Google Benchmark micro-benchmarks of the pipeline's stages, as throughputs
// (voxels/s, triangles/s, tets/s, unknowns/s). Inputs are phantoms generated in code, at sizes where the
// whole suite runs in a few minutes on 2 cores; each stage's input is the previous stage's output.
//   tm-bench-stages --benchmark_out=stages.json --benchmark_out_format=json
#include <benchmark/benchmark.h>

#include "fem/conductivities.h"
#include "fem/solve_potential.h"
#include "image/phantom.h"
#include "surface/decimate.h"
#include "surface/extract_interfaces.h"
#include "surface/smooth.h"
#include "volume/assess.h"
#include "volume/tetrahedralize.h"

using namespace tissuemesh;

namespace {

/// Sizes of the inputs. Lengths in mm.
struct StageInputOptions {
    double voxel_mm = 4;        ///< spheres4 voxel size (4 mm: 0.11 M voxels)
    double max_distance_mm = 1; ///< decimation bound, as the workflow's sphere head
};

/// The chain of inputs, each made once (by the previous stages) and shared by the benchmarks. The tets
/// come from the smoothed surface: at 4 mm, tm-tetra refuses the remeshed one (see bench/RESULTS.md).
struct StageInputs {
    image::Phantom phantom;
    InterfaceComplex extracted, smoothed;
    TetMesh mesh;
};

surface::ExtractOptions extract_options()
{
    return {.priority = {{3, 1}}}; // CSF wins thin places, as the workflow's sphere head
}

StageInputs make_inputs(const StageInputOptions& options)
{
    StageInputs in{image::make_phantom("spheres4", {.voxel_mm = options.voxel_mm}), {}, {}, {}};
    in.extracted = surface::extract_interfaces(in.phantom.image, extract_options());
    in.smoothed = in.extracted;
    surface::smooth(in.smoothed, in.phantom.image);
    in.mesh = volume::tetrahedralize(in.smoothed);
    return in;
}

const StageInputs& inputs()
{
    static const StageInputs shared = make_inputs({});
    return shared;
}

void set_rate(benchmark::State& state, const char* name, std::size_t per_iteration)
{
    state.counters[name] =
        benchmark::Counter(static_cast<double>(per_iteration), benchmark::Counter::kIsIterationInvariantRate);
}

void extraction(benchmark::State& state)
{
    const LabelImage& image = inputs().phantom.image;
    for (auto _ : state) benchmark::DoNotOptimize(surface::extract_interfaces(image, extract_options()));
    set_rate(state, "voxels/s", image.voxel_count());
}

/// Times `edit` on a fresh copy of `input` per iteration (the copy is not timed), as triangles of the input
/// per second.
template <class Edit>
void time_surface_edit(benchmark::State& state, const InterfaceComplex& input, Edit edit)
{
    for (auto _ : state) {
        state.PauseTiming();
        InterfaceComplex complex = input;
        state.ResumeTiming();
        benchmark::DoNotOptimize(edit(complex));
    }
    set_rate(state, "triangles/s", input.triangle_count());
}

void smoothing(benchmark::State& state)
{
    const StageInputs& in = inputs();
    time_surface_edit(state, in.extracted,
                      [&](InterfaceComplex& complex) { return surface::smooth(complex, in.phantom.image); });
}

void decimation(benchmark::State& state)
{
    time_surface_edit(state, inputs().smoothed, [](InterfaceComplex& complex) {
        return surface::decimate(complex, {.max_distance_mm = StageInputOptions{}.max_distance_mm});
    });
}

void tetrahedralization(benchmark::State& state)
{
    const StageInputs& in = inputs();
    for (auto _ : state) benchmark::DoNotOptimize(volume::tetrahedralize(in.smoothed));
    set_rate(state, "tets/s", in.mesh.tet_count());
}

void assessment(benchmark::State& state)
{
    const StageInputs& in = inputs();
    for (auto _ : state) benchmark::DoNotOptimize(volume::assess_elements(in.mesh, in.phantom.image));
    set_rate(state, "tets/s", in.mesh.tet_count());
}

/// tDCS, 1 mA between the temples (as the workflow's sphere head), AMG-CG.
void solve(benchmark::State& state)
{
    const StageInputs& in = inputs();
    const fem::Conductivities sigma = fem::resolve_conductivities(in.mesh, {});
    fem::PotentialProblem problem;
    problem.electrodes = {{.centre_mm = {-86.5, 0, 31.5}, .radius_mm = 10, .current_a = 1e-3},
                          {.centre_mm = {86.5, 0, 31.5}, .radius_mm = 10, .current_a = -1e-3}};
    fem::PotentialReport report;
    for (auto _ : state) benchmark::DoNotOptimize(fem::solve_potential(in.mesh, sigma, problem, {}, {}, &report));
    set_rate(state, "unknowns/s", report.unknowns);
    state.counters["cg_iterations"] = report.solver.iterations;
}

} // namespace

BENCHMARK(extraction)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(smoothing)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(decimation)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(tetrahedralization)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(assessment)->Unit(benchmark::kMillisecond)->MinTime(1.0);
BENCHMARK(solve)->Unit(benchmark::kMillisecond)->Iterations(1);

BENCHMARK_MAIN();
