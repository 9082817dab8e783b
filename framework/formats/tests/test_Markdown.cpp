// Foreign text in esif's Markdown (Markdown.h): a cell stays one cell and
// one line, and no tag or entity of the user's reaches the page.

#include <esif/formats/Markdown.h>

#include <gtest/gtest.h>

namespace
{
TEST(Markdown, AForeignTextStaysOneCellAndNeverHtml)
{
	EXPECT_EQ(esif::markdown::text("a | b"), "a &#124; b");
	EXPECT_EQ(esif::markdown::text("<script>alert(1)</script>"), "&lt;script&gt;alert(1)&lt;/script&gt;");
	EXPECT_EQ(esif::markdown::text("&lt; & <"), "&amp;lt; &amp; &lt;");
	EXPECT_EQ(esif::markdown::text("one\ntwo\r"), "one two ");
	EXPECT_EQ(esif::markdown::text("ref_traj_rms_m *"), "ref_traj_rms_m *");  // emphasis only changes a word's look
	EXPECT_EQ(esif::markdown::lines("a|b\nc<d\n"), "a&#124;b\nc&lt;d\n");
}

}  // namespace
