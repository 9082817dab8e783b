#include <esif/association/SearchBounds.h>

namespace esif
{
void SearchBounds::declare(ParamBinder& b)
{
	b.integer("jcbb_max_candidates", max_candidates,
			  "JCBB is not run when an observation has more individually compatible candidates than this; "
			  "nearest neighbour with the joint compatibility test instead (counted as a fallback)",
			  Bounds::atLeast(1));
	b.real("jcbb_max_hypotheses", max_hypotheses,
		   "JCBB is not run when the product over ambiguous observations of (compatible candidates + 1) exceeds "
		   "this; nearest neighbour with the joint compatibility test instead (counted as a fallback)",
		   Bounds::atLeast(1));
}

}  // namespace esif
