// The --dipole-model names tm-solve, tm-leadfield and tm-bench-eeg accept, and the source model each names.
#pragma once

#include <string>
#include <vector>

#include "fem/solve_potential.h"

namespace tissuemesh::tools {

/// The accepted names, for CLI::IsMember.
inline const std::vector<std::string> dipole_model_names{"venant", "subtraction", "partial-integration"};

/// The model of a name from dipole_model_names (the option's check has refused any other).
inline fem::DipoleModel dipole_model_named(const std::string& name)
{
    if (name == "venant") return fem::DipoleModel::venant;
    if (name == "subtraction") return fem::DipoleModel::subtraction;
    return fem::DipoleModel::partial_integration;
}

} // namespace tissuemesh::tools
