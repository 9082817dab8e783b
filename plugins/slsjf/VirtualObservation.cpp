#include "VirtualObservation.h"

#include <esif/localmap/LocalMapMarginal.h>

#include <utility>

namespace esif::slsjf
{
VirtualObservation keepFeatures(const LocalMap& map, const std::vector<bool>& keep)
{
	LocalMap kept = marginaliseFeatures(map, keep);
	VirtualObservation out;
	for (std::size_t i = 0; i < keep.size(); ++i)
		if (keep[i]) out.kept.push_back(i);
	out.z = kept.state();
	out.information = std::move(kept.information);
	return out;
}

}  // namespace esif::slsjf
