#pragma once
// Loads that could not act: a load whose group has every DOF it acts on held by a support
// would only load the support (a force, a moment) or fight it (a prescribed motion). Refused
// with the load, the group and the DOFs named.
#include "dem/model/model.h"

namespace dembridge::dem
{
/// The DOFs (DofBit mask) load @p l acts on: a force or moment on the translations / rotations
/// whose component is non-zero, a prescribed motion on its prescribed components.
std::uint8_t load_dofs(const Load& l);

/// Validates the pressures (loads.h) of @p c, built into @p m: a positive area, a direction, a
/// ratio load that exists, prescribes motion and has an area; sets Load::ratio_load and makes
/// the directions unit. Throws InputError naming the load and key.
void check_pressure_loads(const CaseConfig& c, Model& m);

/// Throws InputError ("Load NAME/group: ...") for a load of @p m none of whose DOFs is free on
/// any particle of its group (the constraints of every group a particle belongs to count).
void check_loads_act_on_free_dofs(const Model& m);
} // namespace dembridge::dem
