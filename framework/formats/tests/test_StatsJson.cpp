/// \file test_StatsJson.cpp
/// stats.json through nlohmann/json: keys in the order set, numbers,
/// strings and nulls read back with their types, non-finite numbers written
/// as null, and a damaged or foreign file one InputError naming it.

#include <EsifTestSupport.h>

#include <esif/core/Errors.h>
#include <esif/formats/StatsJson.h>

#include <gtest/gtest.h>

#include <fstream>
#include <limits>

namespace
{
using esif::InputError;
using esif::Stats;
using esif::StatValue;

TEST(StatsJson, RoundTripKeepsOrderTypesAndValues)
{
	Stats s;
	s.set("plugin", StatValue(std::string("Slsjf \"quoted\"\nnext line")));
	s.set("steps", StatValue(3000LL));
	s.set("wall_s", StatValue(0.1234567890123456789));
	s.set("tiny", StatValue(1e-300));
	s.set("nan", StatValue(std::numeric_limits<double>::quiet_NaN()));
	s.set("missing", std::optional<double>());
	const Stats back = Stats::fromJson(s.toJson(), "test");
	ASSERT_EQ(back.items().size(), s.items().size());
	for (std::size_t k = 0; k < s.items().size(); ++k) EXPECT_EQ(back.items()[k].first, s.items()[k].first);
	EXPECT_EQ(back.text("plugin"), "Slsjf \"quoted\"\nnext line");
	EXPECT_TRUE(std::holds_alternative<long long>(*back.get("steps")));
	EXPECT_EQ(back.number("wall_s"), 0.1234567890123456789);  // shortest round-trip text: exact
	EXPECT_EQ(back.number("tiny"), 1e-300);
	EXPECT_TRUE(std::holds_alternative<std::nullptr_t>(*back.get("nan")));
	EXPECT_TRUE(std::holds_alternative<std::nullptr_t>(*back.get("missing")));
}

TEST(StatsJson, InvalidUtf8InAPathIsReplacedNotFatal)
{
	Stats s;
	s.set("rawlog", StatValue(std::string("/data/caf\xe9.rawlog")));
	const Stats back = Stats::fromJson(s.toJson(), "test");
	EXPECT_EQ(back.text("rawlog"), "/data/caf\xef\xbf\xbd.rawlog");
}

TEST(StatsJson, DamagedOrForeignTextIsOneErrorNamingTheOrigin)
{
	for (const char* text : {"", "{\"a\": 1", "[1, 2]", "{\"a\": [1]}", "{\"a\": true}", "{\"a\": {\"b\": 1}}",
							 "{\"a\": 18446744073709551615}"})
	{
		try
		{
			Stats::fromJson(text, "run/stats.json");
			ADD_FAILURE() << "accepted: " << text;
		}
		catch (const InputError& e)
		{
			const std::string what = e.what();
			EXPECT_EQ(what.rfind("run/stats.json: ", 0), 0u) << what;
			EXPECT_EQ(what.find('\n'), std::string::npos) << what;
		}
	}
}

TEST(StatsJson, AFileFarLargerThanAnyStatsIsRefusedBeforeReading)
{
	esif::test::TempDir dir;
	const std::string path = dir.file("stats.json");
	{
		std::ofstream out(path);
		out.seekp((32 << 20) - 1);
		out.put('}');
	}
	EXPECT_THROW(Stats::load(path), InputError);
	EXPECT_THROW(Stats::load(dir.file("absent.json")), InputError);
}

}  // namespace
