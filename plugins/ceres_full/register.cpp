// Registers the plugin class with MRPT's RTTI when the library is loaded.
#include "CeresFullSlam.h"

#include <mrpt/core/initializer.h>

MRPT_INITIALIZER(esif_register_ceres_full_plugin) { mrpt::rtti::registerClass(CLASS_ID_NAMESPACE(CeresFullSlam, esif)); }
