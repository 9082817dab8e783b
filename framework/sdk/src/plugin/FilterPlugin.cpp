#include <esif/plugin/FilterPlugin.h>

#include <mrpt/core/initializer.h>

IMPLEMENTS_VIRTUAL_MRPT_OBJECT(FilterPlugin, mrpt::rtti::CObject, esif)

// The abstract base must be registered so getAllRegisteredClassesChildrenOf()
// can find the plugins derived from it.
MRPT_INITIALIZER(esif_register_filter_plugin_base)
{
	mrpt::rtti::registerClass(CLASS_ID_NAMESPACE(FilterPlugin, esif));
}
