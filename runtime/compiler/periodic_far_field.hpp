// Nodes that see the surface only through fract / mod of affine functions of (u, v): a tiling
// (hexagons from two offset mod lattices, circles on a fract grid). Once the footprint covers more
// than a period of every such source, the smoothed value of such a node is its spatial average (a
// Gaussian of sd w periods keeps exp(-2 pi^2 w^2) of the first harmonic: 0.7% at w = 1/2), which no
// moment-propagating rule gives: the Gaussian stand-in for a uniform fract pushed through |.|, max
// and smoothstep drew a hexagonal tiling's far field 0.1-0.3 too dark.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "ir/graph.hpp"

namespace bl::compiler {

class PeriodicFarField {
 public:
  explicit PeriodicFarField(const ir::Graph& g);

  // The fract / mod nodes through which node i alone sees u and v (sorted); empty when i reads any
  // other input, a texture, or u / v by another path, or is constant.
  const std::vector<int>& sources(int i) const { return sources_[i]; }

  // i has sources and is an output, or every path from it to the outputs is +, -, *, / by constants
  // (then the deepest such node: one far field for a mask that mixes several channels' colours):
  // where the far field applies. Only outputs (up to such maps): an intermediate value's
  // spatial moments are not what a nonlinear reader needs (applied to every outermost periodic node,
  // the bump normals that Phong lighting reads and the tiles' fract of value noise and Truchet moved
  // all-Gaussian errors by -5% to +4%: rings +1.7%, value_noise_none +3.6%, truchet -4.7%).
  bool periodic_output(int i) const { return output_[i]; }

  // The period of source j in its argument's units (1 for fract, |c| for mod(x, c)).
  double period(int j) const;

  struct Moments {
    double mean = 0, second = 0;  // spatial mean of the node and of its square
    bool ok = false;              // false: a source is constant over the plane, or a value not finite
  };
  // Over a square covering 32 periods of the longest source, 128 x 128 jittered points of the plain
  // graph (double); memoised for the process by the graph's hash.
  Moments spatial(int i) const;

  // An axis-aligned tiling (every source reads u alone or v alone, their periods commensurate: a
  // common period L per axis): per axis the Fourier series of the output averaged over the other
  // axis, F(x) = a0 + sum_m a_m cos(2 pi m x / L) + b_m sin(2 pi m x / L). Under a Gaussian of sd s
  // along x the m-th term is damped by exp(-2 pi^2 m^2 s^2 / L^2): the exact smoothed value once the
  // footprint covers the other axis (the band below a horizon, where it covers v and not u).
  struct Series {
    int input = -1;     // the axis's input slot; -1: the output does not depend on this axis
    double period = 0;  // L
    double a0 = 0;
    std::vector<double> a, b;  // m = 1..M, trailing terms below kSeriesFloor dropped
  };
  struct Axes {
    bool ok = false;
    Series u, v;
  };
  // M: the first term left out is damped by exp(-2 pi^2 13^2 w^2) < 1.3e-3 for w >= 0.045 (16 terms
  // were as accurate on hex tiles and circles_none, 0.0344 / 0.0200, and cost 1.4x the series'
  // time; 8 terms valid from 0.06 gave 0.0353 / 0.0200 at 0.8x)
  static constexpr int kSeriesTerms = 12;
  static constexpr double kSeriesFloor = 1e-3;  // a term whose |a|, |b| stay below this is not emitted
  // 1024 points along the axis x 128 across (one period each, midpoint rule: a jump of h moves a
  // coefficient by up to ~h / 1024); memoised like spatial().
  Axes axes(int i) const;

 private:
  int surface_slot(const char* name) const;  // the input slot named u or v; -1 if none
  // d/du and d/dv of source j's argument (from the plain graph at (0, 0), (1, 0), (0, 1), once).
  std::pair<double, double> argument_slope(int j) const;

  const ir::Graph& g_;
  std::vector<std::vector<int>> sources_;
  std::vector<bool> output_;
  mutable std::uint64_t hash_ = 0;
  mutable std::vector<double> at00_, at10_, at01_;  // argument_slope's plain graphs
};

}  // namespace bl::compiler
