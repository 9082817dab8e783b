#pragma once
/// \file SlsjfParams.h
/// Parameters of the SLSJF plugin, INI section [slsjf]: the global data
/// association (Sec. 5.4.1), the optional relinearisation of all fused maps
/// (iterated SLSJF), the local-map builder and the sparse recovery.

#include "GlobalMap.h"

#include <esif/config/ParamBinder.h>
#include <esif/localmap/LocalMapBuilderParams.h>
#include <esif/localmap/MapLevelAssociationParams.h>
#include <esif/sparse/SparseRecoveryParams.h>

namespace esif::slsjf
{
/// Relinearisation of every fused local map at the current estimate
/// (Gauss-Newton over the local-map formulation, after the authors' I-SLSJF).
enum class Smoothing
{
	None,		 ///< plain SLSJF (the book's filter)
	Final,		 ///< once, after the last map
	EveryKMaps	 ///< after every smoothing_every_maps maps, and after the last
};

/// The global association (MapLevelAssociationParams: with jcbb or nn, on
/// the features of the earlier maps the new one can overlap, Sec. 5.4.1; an
/// ambiguous local feature is marginalised from the local map) and the rest.
struct SlsjfParams : MapLevelAssociationParams
{
	/// Slack of the overlap test between local maps and of the candidates'
	/// distance to the new map's features (the authors' EstBias) [m]. 2 m
	/// suits the book's simulations (features 3 m apart, 5 m range); the
	/// authors use 30 m on Victoria Park. Measurements behind the default:
	/// docs/plugins/slsjf.md, "Defaults".
	double overlap_margin_m = 2.0;
	/// Sigmas added to local-map radii and to the start-pose uncertainty in
	/// the overlap test (the authors' SigmaMultiplier).
	double overlap_sigmas = 3.0;

	/// Where each fusion is linearised (GlobalMap.h): the book's current
	/// estimate, each variable's first estimate (FEJ), or the current one
	/// constrained to the first estimates' null space.
	FusionJacobians jacobians = FusionJacobians::Current;

	Smoothing smoothing = Smoothing::None;	///< none | final | every_k_maps
	int smoothing_every_maps = 50;	///< K of every_k_maps
	int smoothing_max_iterations = 10;	///< Gauss-Newton iterations per relinearisation
	/// Relinearisation stops when no estimate moves more than this (metres
	/// for positions, radians for headings).
	double smoothing_tolerance = 1e-4;

	LocalMapBuilderParams builder;	///< local maps built from a rawlog
	/// Recovery, reordering and when to reorder (Sec. 5.4.2, 3.3.2).
	/// SLSJF's defaults: unconstrained nested dissection, rebuilt when the
	/// factor has filled in by 20%, chosen against the book's trigger (CAMD,
	/// n0 = 1000) and against AMD on grid1225_large's 401 maps and the city
	/// scenarios (docs/plugins/slsjf.md, "Defaults", has the measurements).
	SparseRecoveryParams recovery = defaultRecovery();

	void declare(ParamBinder& b);
	static SparseRecoveryParams defaultRecovery();
};

}  // namespace esif::slsjf
