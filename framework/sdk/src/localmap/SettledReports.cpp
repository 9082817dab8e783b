#include "localmap/SettledReports.h"

#include <map>

namespace esif
{
void appendSettledReports(const std::vector<StepReport>& step_reports, const std::vector<LandmarkId>& local_ids,
						  const StepReport& decisions, std::set<LandmarkId>& started, std::vector<StepReport>& out)
{
	std::map<LandmarkId, const Association*> decision_of;
	for (std::size_t i = 0; i < local_ids.size() && i < decisions.associations.size(); ++i)
		decision_of[local_ids[i]] = &decisions.associations[i];
	for (StepReport report : step_reports)
	{
		for (auto& a : report.associations)
		{
			if (a.kind == Association::Kind::Rejected) continue;
			const auto it = decision_of.find(a.id);
			if (it == decision_of.end() || it->second->kind == Association::Kind::Rejected)
			{
				a = {Association::Kind::Rejected, -1};
				continue;
			}
			a.id = it->second->id;
			a.kind = started.insert(a.id).second ? Association::Kind::New : Association::Kind::Matched;
		}
		out.push_back(std::move(report));
	}
}

}  // namespace esif
