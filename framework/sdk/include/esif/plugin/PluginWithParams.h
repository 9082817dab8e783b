#pragma once
/// \file PluginWithParams.h
/// configure() and parameters() written once for every plugin whose
/// parameters are one struct with a `declare(ParamBinder&)` member
/// (ParamBinder.h). A plugin derives from PluginWithParams<Params> (or
/// PluginWithParams<Params, MapJoiningPlugin>) and implements, if it needs
/// them, two hooks:
/// - validate(params, section): the rules between keys (each key's own
///   bounds are checked by its declaration); throw ConfigError naming the
///   keys through section.describeKey(). Never clamp a value silently.
/// - start(): build what the parameters size (filters, maps, graphs).
/// configure() loads every declared key, calls validate(), stores the
/// parameters, starts a map-joining plugin's local-map builder with
/// `params.builder`, then calls start().

#include <esif/config/ConfigSection.h>
#include <esif/config/ParamBinder.h>
#include <esif/plugin/FilterPlugin.h>
#include <esif/plugin/MapJoiningPlugin.h>

#include <type_traits>
#include <utility>
#include <vector>

namespace esif
{
template <class Params, class Base = FilterPlugin>
class PluginWithParams : public Base
{
	static_assert(std::is_base_of_v<FilterPlugin, Base>, "PluginWithParams: Base must be a FilterPlugin");

   public:
	void configure(const ConfigSection& section) final
	{
		Params params;
		loadParams(params, section);
		validate(params, section);
		params_ = std::move(params);
		if constexpr (std::is_base_of_v<MapJoiningPlugin, Base>) this->startBuilder(params_.builder);
		start();
	}

	std::vector<ParamInfo> parameters() const final { return describeParams(params_); }

   protected:
	using Base::Base;

	/// Rules between keys; ConfigError naming them. Default: none.
	virtual void validate(const Params& /*params*/, const ConfigSection& /*section*/) const {}
	/// Builds what the parameters size; called once, after validate().
	virtual void start() {}

	Params params_;	 ///< as configured (the defaults before configure())
};

}  // namespace esif
