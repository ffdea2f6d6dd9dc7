// json_locate against positions counted by hand in small texts.
#include "glint/base/json_locate.h"

#include <gtest/gtest.h>

#include <string>

namespace glint {
namespace {

std::string where(std::string_view text, std::string_view pointer) {
    const auto p = json_locate(text, pointer);
    return p ? std::to_string(p->line) + ":" + std::to_string(p->column) : "none";
}

TEST(JsonLocate, FindsValuesAlongThePointer) {
    // Lines and columns counted by hand.
    const std::string text =
        "{\n"                                               // 1
        "  \"asset\": {\"version\": \"2.0\"},\n"            // 2
        "  \"nodes\": [\n"                                  // 3
        "    {\"name\": \"a \\\"quoted\\\" {[\", \"mesh\": 0},\n"  // 4
        "    {\"children\": [0, 2], \"mesh\": 7}\n"         // 5
        "  ],\n"                                            // 6
        "  \"a/b\": {\"m~n\": true}\n"                      // 7
        "}\n";
    EXPECT_EQ(where(text, ""), "1:1");
    EXPECT_EQ(where(text, "/asset"), "2:12");
    EXPECT_EQ(where(text, "/asset/version"), "2:24");
    EXPECT_EQ(where(text, "/nodes"), "3:12");
    EXPECT_EQ(where(text, "/nodes/0"), "4:5");
    EXPECT_EQ(where(text, "/nodes/0/mesh"), "4:41");  // past a string holding quotes and brackets
    EXPECT_EQ(where(text, "/nodes/1/mesh"), "5:34");
    EXPECT_EQ(where(text, "/nodes/1/children/1"), "5:22");
    EXPECT_EQ(where(text, "/a~1b/m~0n"), "7:18");
    // Absent values, wrong kinds, bad pointers.
    EXPECT_EQ(where(text, "/nodes/2"), "none");
    EXPECT_EQ(where(text, "/nodes/x"), "none");
    EXPECT_EQ(where(text, "/meshes"), "none");
    EXPECT_EQ(where(text, "/asset/version/0"), "none");
    EXPECT_EQ(where(text, "nodes"), "none");
}

TEST(JsonLocate, ColumnsCountCharactersNotBytes) {
    EXPECT_EQ(where("{\"n\u00e9\": 1, \"x\": 2}", "/x"), "1:16");  // é is two bytes, one column
}

TEST(JsonLocate, MalformedOrDeepTextsEndInAnAnswer) {
    EXPECT_EQ(where("", "/a"), "none");
    EXPECT_EQ(where("{\"a\": ", "/a"), "none");
    EXPECT_EQ(where("{\"a\": [1, 2", "/a/5"), "none");
    EXPECT_EQ(where("{\"a", "/a"), "none");
    EXPECT_EQ(where("[\"\\", "/1"), "none");
    // A million nested brackets before the target are skipped without recursion.
    const std::string deep = "[" + std::string(1000000, '[') + std::string(1000000, ']') + ", 5]";
    EXPECT_EQ(where(deep, "/1"), "1:2000004");
    // Every truncation of a text gives an answer (the value is found only if it is complete enough).
    const std::string t = "{\"a\": [{\"b\": \"x\"}, {\"c\": [1, {\"d\": null}]}]}";
    for (std::size_t n = 0; n <= t.size(); ++n) (void)json_locate(t.substr(0, n), "/a/1/c/1/d");
    EXPECT_EQ(where(t, "/a/1/c/1/d"), "1:36");
}

}  // namespace
}  // namespace glint
