// gi.budget_policy: whether GI only reports going over the platform profile's budget (fixed) or
// the budget scheduler lowers its load to stay inside it (adapt, gi/GiScheduler.h). The setting is
// declared next to the scheduler, in GiScheduler.cpp; LpvSettings carries its value.
#pragma once

#include "engine/config/Config.h"

#include <string_view>

namespace lpv::gi {

enum class GiBudgetPolicy { Fixed, Adapt };

GiBudgetPolicy readGiBudgetPolicy(const engine::Config& config);
std::string_view giBudgetPolicyName(GiBudgetPolicy policy);

} // namespace lpv::gi
