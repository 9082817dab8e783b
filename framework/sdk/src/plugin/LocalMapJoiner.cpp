#include <esif/plugin/LocalMapJoiner.h>

namespace esif
{
// Out of line so the interface's type information lives in the framework
// library: the host's dynamic_cast then works across the plugin modules.
LocalMapJoiner::~LocalMapJoiner() = default;

}  // namespace esif
