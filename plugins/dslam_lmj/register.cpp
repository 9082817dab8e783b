// Registers the plugin class with MRPT's RTTI when the library is loaded.
#include "DslamLocalMapJoining.h"

#include <mrpt/core/initializer.h>

MRPT_INITIALIZER(esif_register_dslam_lmj_plugin)
{
	mrpt::rtti::registerClass(CLASS_ID_NAMESPACE(DslamLocalMapJoining, esif));
}
