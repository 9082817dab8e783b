// Registers the plugin class with MRPT's RTTI when the library is loaded.
#include "Slsjf.h"

#include <mrpt/core/initializer.h>

MRPT_INITIALIZER(esif_register_slsjf_plugin) { mrpt::rtti::registerClass(CLASS_ID_NAMESPACE(Slsjf, esif)); }
