// The in-situ (initial) stress of a scene ("insitu_stress": {...}; docs/staged-analysis.md):
// given by its components and their gradients with depth, or by the overburden shortcut K0.
// The solver's side is solver/discretisation/insitu_stress.h.
#pragma once

namespace nmm {

class JsonReader;
struct SceneDef;

/// Initial stress σ(x, y) = σ0 + (y_ref − y)·gradient, Pa, tension positive.
struct InsituStressDef {
  bool present = false;
  double sxx = 0, syy = 0, sxy = 0;     ///< Pa, σ0 at y = y_ref
  double y_ref = 0;                     ///< m
  double gxx = 0, gyy = 0, gxy = 0;     ///< Pa per m of depth below y_ref
};

/// insitu_stress: {sxx, syy, sxy, y_ref, gradient: [gxx, gyy, gxy]} or the overburden shortcut
/// {k0, y_ref, density (default: the first material's), syy (at y_ref, default 0), g (default
/// |gravity|, else 9.81)}. Reads the scene's materials and gravity (read before).
InsituStressDef read_insitu(const JsonReader& r, const SceneDef& scene);

}  // namespace nmm
