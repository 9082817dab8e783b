#pragma once
/// \file MrptMatrix.h
/// Eigen matrices handed to MRPT's data association (mrpt::slam), which
/// takes its own matrix type.

#include <mrpt/math/CMatrixDynamic.h>

#include <Eigen/Core>

namespace esif
{
inline mrpt::math::CMatrixDouble toMrpt(const Eigen::MatrixXd& m)
{
	mrpt::math::CMatrixDouble out(m.rows(), m.cols());
	out.asEigen() = m;
	return out;
}

}  // namespace esif
