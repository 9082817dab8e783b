#pragma once
/// \file QuietCeresLogging.h
/// Ceres reports through glog, a few lines on stderr per event (e.g. "Jacobian
/// matrix is rank deficient", preceded by glog's own notice that it was not
/// initialised). The plugin says what went wrong in one line of its own and
/// in its stats, so glog's messages below FATAL are held back while it runs.
/// (CHOLMOD prints some errors itself, past glog: those remain.)

#include <glog/logging.h>

namespace esif::ceres_full
{
class QuietCeresLogging
{
   public:
	QuietCeresLogging() : saved_(FLAGS_minloglevel) { FLAGS_minloglevel = google::GLOG_FATAL; }
	~QuietCeresLogging() { FLAGS_minloglevel = saved_; }
	QuietCeresLogging(const QuietCeresLogging&) = delete;
	QuietCeresLogging& operator=(const QuietCeresLogging&) = delete;

   private:
	int saved_;
};

}  // namespace esif::ceres_full
