// Scene nodes: children are removed with their subtree, only by their own parent.
#include <gtest/gtest.h>

#include "engine/scene/node.h"

namespace {

TEST(SceneNode, RemoveChildDestroysTheSubtreeAndOnlyDirectChildren) {
    engine::Node root("root");
    engine::Node& a = root.add_child("a");
    engine::Node& b = root.add_child("b");
    engine::Node& grandchild = a.add_child("a.1");
    EXPECT_FALSE(root.remove_child(grandchild)) << "not a direct child";
    EXPECT_FALSE(b.remove_child(a)) << "a sibling";
    EXPECT_TRUE(root.remove_child(a));
    ASSERT_EQ(root.children().size(), 1u);
    EXPECT_EQ(root.children().front().get(), &b);
    int visited = 0;
    root.visit([&](const engine::Node&) { ++visited; });
    EXPECT_EQ(visited, 2) << "root and b; a and its child are gone";
}

}  // namespace
