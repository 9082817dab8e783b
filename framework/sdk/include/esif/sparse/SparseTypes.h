#pragma once
/// \file SparseTypes.h
/// Variables of the sparse information form: blocks of 2 (a point feature
/// x, y) or 3 (a robot pose x, y, theta) scalars, named by a VarId.

namespace esif
{
/// Index of a block variable, in order of creation (0, 1, 2, ...).
struct VarId
{
	int value = -1;

	bool operator==(VarId o) const { return value == o.value; }
	bool operator!=(VarId o) const { return value != o.value; }
	bool operator<(VarId o) const { return value < o.value; }
};

/// What a block variable is; its dimension follows.
enum class VarKind
{
	Point2,  ///< 2-D point feature (x, y) [m]
	Pose2    ///< 2-D pose (x [m], y [m], theta [rad])
};

/// Number of scalars of a variable of kind `k`.
constexpr int varDim(VarKind k)
{
	return k == VarKind::Point2 ? 2 : 3;
}

/// "point" or "pose", for messages.
constexpr const char* varKindName(VarKind k)
{
	return k == VarKind::Point2 ? "point" : "pose";
}

}  // namespace esif
