#pragma once
/// \file QuietCeresLogging.h
/// Ceres reports through glog, a few lines on stderr per event (e.g. "Jacobian
/// matrix is rank deficient", or a residual block's dump when it evaluates
/// to NaN, preceded by glog's own notice that it was not initialised), and
/// the SuiteSparse routines it calls print their own errors (e.g. "CHOLMOD
/// error: invalid xtype" from its covariance code on a non-finite Jacobian)
/// through SuiteSparse's printf hook. The plugin says what went wrong in one
/// line of its own and in its stats, so while it runs, glog's messages below
/// FATAL are held back and SuiteSparse's printf hook is unset. Every call
/// into Ceres (Solve, Evaluate, Covariance) holds one.

#include <SuiteSparse_config.h>
#include <glog/logging.h>

namespace esif::ceres_full
{
class QuietCeresLogging
{
   public:
	QuietCeresLogging() : saved_level_(FLAGS_minloglevel), saved_printf_(SuiteSparse_config.printf_func)
	{
		FLAGS_minloglevel = google::GLOG_FATAL;
		SuiteSparse_config.printf_func = nullptr;  // SuiteSparse then prints nothing
	}
	~QuietCeresLogging()
	{
		FLAGS_minloglevel = saved_level_;
		SuiteSparse_config.printf_func = saved_printf_;
	}
	QuietCeresLogging(const QuietCeresLogging&) = delete;
	QuietCeresLogging& operator=(const QuietCeresLogging&) = delete;

   private:
	int saved_level_;
	int (*saved_printf_)(const char*, ...);
};

}  // namespace esif::ceres_full
