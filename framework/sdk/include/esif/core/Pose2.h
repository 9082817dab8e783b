#pragma once
/// \file Pose2.h
/// The SDK's one pose type. The SE(2) operations on it are in
/// esif/models/Se2.h.

#include <Eigen/Core>

namespace esif
{
using Pose2 = Eigen::Vector3d;	///< (x [m], y [m], phi [rad]); (2) = heading
}  // namespace esif
