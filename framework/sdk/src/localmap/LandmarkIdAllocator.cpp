#include <esif/localmap/LandmarkIdAllocator.h>

#include <algorithm>

namespace esif
{
LandmarkId LandmarkIdAllocator::allocate(LandmarkId proposed, const std::function<bool(LandmarkId)>& taken)
{
	LandmarkId id = proposed >= 0 && !taken(proposed) ? proposed : next_free_;
	while (taken(id)) ++id;
	next_free_ = std::max(next_free_, id + 1);
	return id;
}

}  // namespace esif
