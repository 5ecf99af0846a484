// Several compartments running the same controller, docked to each other: the in-process form
// of what the arena does over the bus. A packet sent in tick t is received at the start of
// t + 1, summed in increasing order of sender id, exactly as ahhs-module does it.
#pragma once

#include <vector>

#include "modules/core/hormone_system.h"

namespace ahhs::modules {

class Organism {
 public:
  // neighbours[c] lists the compartments docked to c. Docking must be symmetric, without
  // self-links or duplicates, and at most controller.ports() per compartment; otherwise throws
  // std::invalid_argument. `controller` must outlive the organism.
  Organism(const Controller& controller, std::vector<std::vector<int>> neighbours);

  // Compartments 0..n-1 docked in a line (the gait chain; n = 2 is the pendulum's pair).
  static std::vector<std::vector<int>> Chain(int n);

  // One tick of every compartment; inputs[c] is compartment c's TickInput (num_neighbours is
  // filled in from the docking).
  void Step(const std::vector<TickInput>& inputs);

  int size() const { return static_cast<int>(states_.size()); }
  const CompartmentState& state(int c) const { return states_[static_cast<std::size_t>(c)]; }
  CompartmentState& mutable_state(int c) { return states_[static_cast<std::size_t>(c)]; }
  const std::vector<int>& neighbours(int c) const {
    return neighbours_[static_cast<std::size_t>(c)];
  }

  // Total hormone h in the organism, including packets on their way (for conservation checks).
  double TotalHormone(int h) const;

 private:
  const Controller& controller_;
  std::vector<std::vector<int>> neighbours_;
  std::vector<CompartmentState> states_;
  std::vector<Eigen::VectorXd> in_flight_;  // outflow of each compartment, delivered next tick
};

}  // namespace ahhs::modules
