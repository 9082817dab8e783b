#include "sparse/StaircaseUpdate.h"

#include <Eigen/QR>
#include <algorithm>

namespace esif
{
Eigen::MatrixXd staircase(const Eigen::MatrixXd& C)
{
	if (C.rows() < 1 || C.cols() < 2) return C;
	const Eigen::HouseholderQR<Eigen::MatrixXd> qr(C.transpose());
	const Eigen::Index k = std::min(C.rows(), C.cols());
	return qr.matrixQR().topRows(k).triangularView<Eigen::Upper>().transpose();
}

}  // namespace esif
