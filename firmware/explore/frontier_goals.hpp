// Frontier goals: goals just beyond what a module has reached (an exploration strategy beyond
// SPEC §2.3, off by default). Each module of one or two dimensions keeps a coarse occupancy
// grid over its goal region (kFrontierCells per side): a cell is "reached" once any archived
// outcome projects into it. A frontier cell is an unreached cell with a reached neighbour (8-
// neighbourhood). A frontier goal is a uniform point in a frontier cell drawn with weight
// 1 / (1 + misses)², where misses counts the steps aimed at that cell that left it unreached:
// cells beyond what the arm can reach (outside the unit disc) fade instead of absorbing goals.
// Everything it uses is the agent's own: its outcomes (what it observed) and its goals.
//
// Memory: kMaxModules × kFrontierCells² × 2 bytes (11.5 KB), no heap; O(cells) per goal.
// Determinism: draws only from the Prng it is given (the Explorer's frontier stream).
#pragma once
#include <cstdint>

#include "firmware/explore/config.hpp"
#include "firmware/explore/goal_module.hpp"
#include "firmware/explore/prng.hpp"

namespace curio {

inline constexpr int kFrontierCells = 24;  // per side; not the 30×30 grid of the metric (§4)
static_assert(kFrontierCells >= 3 && kFrontierCells <= 255, "cells fit in a byte index");

class FrontierGoals {
 public:
  // Forgets everything; modules with more than two dimensions get no grid (frontier goals are
  // then never drawn for them).
  void reset(const GoalModule* modules, int n_modules);

  // One archived outcome, projected onto module k (its n_dims values).
  void observe(int k, const float* projected);

  // Draws a frontier goal for module k into goal (n_dims values); false when module k has no
  // grid or no frontier cell (the caller samples SPEC's goal instead). Remembers the cell.
  bool sample(int k, Prng& prng, float* goal);

  // After the step aimed at the last sampled cell of module k: a miss if it is still unreached.
  void step_done(int k);

  bool has_grid(int k) const { return has_grid_[k]; }
  int reached_cells(int k) const;

 private:
  int cell_of(int k, const float* projected) const;
  bool reached(int k, int cx, int cy) const;
  // Draw weight of cell (cx, cy) of module k: 0 unless it is a frontier cell.
  double weight(int k, int cx, int cy) const;

  static constexpr int kCells = kFrontierCells * kFrontierCells;
  uint8_t reached_[kMaxModules][kCells] = {};
  uint8_t misses_[kMaxModules][kCells] = {};
  float lo_[kMaxModules] = {};
  float width_[kMaxModules] = {};  // of one cell
  int dims_[kMaxModules] = {};
  bool has_grid_[kMaxModules] = {};
  int aimed_[kMaxModules] = {};  // cell of the last frontier goal, -1: none
};

}  // namespace curio
