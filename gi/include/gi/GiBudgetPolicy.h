// gi.budget_policy: whether GI only reports going over the platform profile's budget (fixed) or
// the budget scheduler lowers its load to stay inside it (adapt, gi/GiScheduler.h). The setting is
// read by the engine's adapter (gi/adapter/LpvConfig.h); LpvSettings carries its value.
#pragma once

#include <string_view>

namespace lpv::gi {

enum class GiBudgetPolicy { Fixed, Adapt };

std::string_view giBudgetPolicyName(GiBudgetPolicy policy);

} // namespace lpv::gi
