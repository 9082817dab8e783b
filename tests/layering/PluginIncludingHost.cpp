// Built only by the ctest "plugin_cannot_include_host", which passes when
// this fails to compile: a plugin links esif::sdk, whose include path holds
// no host header, so a plugin cannot reach into the host.
#include <esif/plugin/FilterPlugin.h>
#include <esif/run/Replay.h>
