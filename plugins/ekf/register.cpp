// Registers the plugin class with MRPT's RTTI when the library is loaded.
#include "EkfSlam.h"

#include <mrpt/core/initializer.h>

MRPT_INITIALIZER(esif_register_ekf_plugin) { mrpt::rtti::registerClass(CLASS_ID_NAMESPACE(EkfSlam, esif)); }
