#pragma once
// An FE dynamics run's checkpoints (fem/fem_case.h) on the app's checkpoint file
// (app/checkpoint/checkpoint.h): written at Output/checkpoint interval or wall interval, read
// back on --resume.
#include "app/checkpoint/checkpoint.h"
#include "fem/fem_case.h"
#include <deal.II/base/parameter_handler.h>

namespace dembridge::app
{
/// The checkpoints of an FE dynamics run on the checkpoint file of @p checkpoint (none when the
/// run writes no checkpoints).
fem::DynamicsCheckpoints fem_checkpoints(const dealii::ParameterHandler& prm,
                                         const CheckpointSettings& checkpoint);
} // namespace dembridge::app
