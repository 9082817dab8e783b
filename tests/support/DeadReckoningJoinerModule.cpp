// Registers the test-only joining plugin when its module is loaded (the
// tests build it into their own folder and pass it with --plugin-dir).
#include "DeadReckoningJoiner.h"

#include <mrpt/core/initializer.h>

MRPT_INITIALIZER(esif_register_dead_reckoning_joiner)
{
	mrpt::rtti::registerClass(CLASS_ID_NAMESPACE(DeadReckoningJoiner, esif::test));
}
