#include "modules/core/organism.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace ahhs::modules {

Organism::Organism(const Controller& controller, std::vector<std::vector<int>> neighbours)
    : controller_(controller), neighbours_(std::move(neighbours)) {
  const int n = static_cast<int>(neighbours_.size());
  if (n < 1) throw std::invalid_argument("an organism needs at least one compartment");
  for (int c = 0; c < n; ++c) {
    auto& list = neighbours_[static_cast<std::size_t>(c)];
    std::sort(list.begin(), list.end());
    const std::string where = "compartment " + std::to_string(c) + ": ";
    if (std::adjacent_find(list.begin(), list.end()) != list.end())
      throw std::invalid_argument(where + "docked twice to the same neighbour");
    if (static_cast<int>(list.size()) > controller.ports())
      throw std::invalid_argument(where + "more neighbours than docking ports");
    for (int other : list) {
      if (other < 0 || other >= n || other == c)
        throw std::invalid_argument(where + "bad neighbour id " + std::to_string(other));
      const auto& back = neighbours_[static_cast<std::size_t>(other)];
      if (std::find(back.begin(), back.end(), c) == back.end())
        throw std::invalid_argument(where + "docking to " + std::to_string(other) +
                                    " is one-sided");
    }
  }
  states_.assign(static_cast<std::size_t>(n), MakeState(controller));
  in_flight_.assign(static_cast<std::size_t>(n), Eigen::VectorXd::Zero(controller.num_hormones()));
}

std::vector<std::vector<int>> Organism::Chain(int n) {
  std::vector<std::vector<int>> links(static_cast<std::size_t>(std::max(n, 0)));
  for (int c = 0; c + 1 < n; ++c) {
    links[static_cast<std::size_t>(c)].push_back(c + 1);
    links[static_cast<std::size_t>(c + 1)].push_back(c);
  }
  return links;
}

void Organism::Step(const std::vector<TickInput>& inputs) {
  if (inputs.size() != states_.size()) throw std::invalid_argument("one TickInput per compartment");
  for (std::size_t c = 0; c < states_.size(); ++c) {
    for (int from : neighbours_[c])
      ReceiveHormones(in_flight_[static_cast<std::size_t>(from)].data(), &states_[c]);
    TickInput input = inputs[c];
    input.num_neighbours = static_cast<int>(neighbours_[c].size());
    modules::Step(controller_, input, &states_[c]);
  }
  for (std::size_t c = 0; c < states_.size(); ++c) in_flight_[c] = states_[c].outflow;
}

double Organism::TotalHormone(int h) const {
  double total = 0;
  for (std::size_t c = 0; c < states_.size(); ++c) {
    total += states_[c].hormones[h];
    total += static_cast<double>(neighbours_[c].size()) * in_flight_[c][h];
  }
  return total;
}

}  // namespace ahhs::modules
