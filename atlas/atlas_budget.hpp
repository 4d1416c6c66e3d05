#pragma once
// The atlas's budget (docs/atlas.md, "The grid, the budget and the cache"): how much of --budget
// each family may plan, and the atlas.json row of a setting left out for it.
#include <algorithm>
#include <nlohmann/json_fwd.hpp>

#include "models/model_setting.hpp"

namespace granvv::app {

// How much of --budget a family of rungs may plan: the budget left over the families left to
// plan, so that what one family leaves passes to the next (docs/atlas.md).
class BudgetShares {
 public:
  BudgetShares(double budget, int families) : budget_(budget), left_(std::max(1, families)) {}
  // The share of the next family; its use is then charged with spend and closed with done.
  double share() const { return std::max(0.0, budget_ - used_) / left_; }
  void spend(double seconds) { used_ += seconds; }
  void done() { left_ = std::max(1, left_ - 1); }

 private:
  double budget_;
  int left_;
  double used_ = 0.0;
};

// atlas.json `skipped` row: a setting whose estimate would pass its family's share.
nlohmann::json skipped_for_budget(const AtlasSetting& s, double estimate, double share,
                                  double budget);

}  // namespace granvv::app
