#include <esif/core/MeasurementSubset.h>

namespace esif
{
MeasurementSubset measurementSubset(
	const Scan& scan, const std::function<bool(std::size_t i, const RangeBearing& m)>& keep)
{
	MeasurementSubset out;
	out.scan = scan;
	out.scan.measurements.clear();
	out.whole = scan.measurements.size();
	for (std::size_t i = 0; i < scan.measurements.size(); ++i)
		if (keep(i, scan.measurements[i]))
		{
			out.scan.measurements.push_back(scan.measurements[i]);
			out.kept.push_back(i);
		}
	return out;
}

StepReport MeasurementSubset::spread(const StepReport& on_part) const
{
	StepReport report;
	report.associations.assign(whole, Association{Association::Kind::Rejected, -1});
	for (std::size_t u = 0; u < kept.size(); ++u) report.associations[kept[u]] = on_part.associations[u];
	return report;
}

}  // namespace esif
