// The components shipped with tsrir_sim, registered once on the registry's first use.
// New built-ins: one register_builtin() line in components.cc.
#pragma once
#include <string>

#include "sim/model.h"

namespace tsrir::sim {

void register_builtin_components();
// Only for use inside register_builtin_components() (the registry lock is not taken there).
void register_builtin(const std::string& name, const std::string& description, ComponentFactory factory);
void register_builtin_alias(const std::string& alias, const std::string& expansion);

}  // namespace tsrir::sim
