#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/message_bus.h"
#include "plugin_msgs/plugin_msgs.h"

using engine::MessageBus;
using engine::Subscription;
using plugin_msgs::CameraState;
using plugin_msgs::FrameStatistics;

namespace {

FrameStatistics frame(std::uint64_t index) {
    FrameStatistics stats;
    stats.frame_index = index;
    return stats;
}

}  // namespace

TEST(MessageBus, DeliversToSubscribersInSubscriptionOrder) {
    MessageBus bus;
    std::vector<std::string> calls;
    const auto a = bus.subscribe<FrameStatistics>(
        [&](const FrameStatistics& m) { calls.push_back("a" + std::to_string(m.frame_index)); });
    const auto b = bus.subscribe<FrameStatistics>(
        [&](const FrameStatistics& m) { calls.push_back("b" + std::to_string(m.frame_index)); });
    bus.publish(frame(1));
    bus.publish(frame(2));
    EXPECT_EQ(calls, (std::vector<std::string>{"a1", "b1", "a2", "b2"}));
}

TEST(MessageBus, UnsubscribesWhenSubscriptionIsDestroyedOrReset) {
    MessageBus bus;
    int calls = 0;
    {
        const auto scoped = bus.subscribe<FrameStatistics>([&](const FrameStatistics&) { ++calls; });
        EXPECT_EQ(bus.subscriber_count(FrameStatistics::kind), 1u);
        bus.publish(frame(1));
    }
    EXPECT_EQ(bus.subscriber_count(FrameStatistics::kind), 0u);
    bus.publish(frame(2));
    EXPECT_EQ(calls, 1);

    auto reset = bus.subscribe<FrameStatistics>([&](const FrameStatistics&) { ++calls; });
    reset.reset();
    reset.reset();  // a second reset is harmless
    bus.publish(frame(3));
    EXPECT_EQ(calls, 1);
}

TEST(MessageBus, MovedSubscriptionStaysSubscribedOnce) {
    MessageBus bus;
    int calls = 0;
    Subscription outer;
    {
        auto inner = bus.subscribe<FrameStatistics>([&](const FrameStatistics&) { ++calls; });
        outer = std::move(inner);
    }  // the moved-from subscription must not unsubscribe
    bus.publish(frame(1));
    EXPECT_EQ(calls, 1);
    EXPECT_EQ(bus.subscriber_count(FrameStatistics::kind), 1u);
    outer = Subscription();  // assigning over it unsubscribes
    EXPECT_EQ(bus.subscriber_count(FrameStatistics::kind), 0u);
}

TEST(MessageBus, HandlerMayUnsubscribeItselfDuringDelivery) {
    MessageBus bus;
    int once_calls = 0;
    int other_calls = 0;
    Subscription once;
    once = bus.subscribe<FrameStatistics>([&](const FrameStatistics&) {
        ++once_calls;
        once.reset();
    });
    const auto other = bus.subscribe<FrameStatistics>([&](const FrameStatistics&) { ++other_calls; });
    bus.publish(frame(1));
    bus.publish(frame(2));
    EXPECT_EQ(once_calls, 1);
    EXPECT_EQ(other_calls, 2);  // delivery to the rest continued
}

TEST(MessageBus, HandlerMayPublishAndSubscribeDuringDelivery) {
    MessageBus bus;
    std::vector<std::string> calls;
    Subscription late;
    bool subscribed_late = false;
    const auto relay = bus.subscribe<FrameStatistics>([&](const FrameStatistics& m) {
        calls.push_back("frame");
        CameraState camera;
        camera.frame_index = m.frame_index;
        bus.publish(camera);  // nested delivery of another kind, to completion
        if (std::exchange(subscribed_late, true)) return;
        late = bus.subscribe<FrameStatistics>([&](const FrameStatistics&) { calls.push_back("late"); });
    });
    const auto camera_listener = bus.subscribe<CameraState>(
        [&](const CameraState& m) { calls.push_back("camera" + std::to_string(m.frame_index)); });
    bus.publish(frame(7));
    // A subscriber added during delivery starts with the next message.
    EXPECT_EQ(calls, (std::vector<std::string>{"frame", "camera7"}));
    bus.publish(frame(8));
    EXPECT_EQ(calls, (std::vector<std::string>{"frame", "camera7", "frame", "camera8", "late"}));
    ASSERT_TRUE(bus.latest<CameraState>().has_value());
    EXPECT_EQ(bus.latest<CameraState>()->frame_index, 8u);
}

TEST(MessageBus, LatestKeepsTheLastMessageOfEachKind) {
    MessageBus bus;
    EXPECT_FALSE(bus.latest<FrameStatistics>().has_value());
    bus.publish(frame(1));
    bus.publish(frame(2));  // kept even without subscribers
    ASSERT_TRUE(bus.latest<FrameStatistics>().has_value());
    EXPECT_EQ(*bus.latest<FrameStatistics>(), frame(2));
    EXPECT_FALSE(bus.latest<CameraState>().has_value());
}

TEST(MessageBus, KeepsKindsApart) {
    MessageBus bus;
    int frames = 0;
    int cameras = 0;
    int work = 0;
    const auto a = bus.subscribe<FrameStatistics>([&](const FrameStatistics&) { ++frames; });
    const auto b = bus.subscribe<CameraState>([&](const CameraState&) { ++cameras; });
    const auto c = bus.subscribe<plugin_msgs::BackgroundWork>([&](const plugin_msgs::BackgroundWork&) { ++work; });
    bus.publish(frame(1));
    bus.publish(CameraState{});
    bus.publish(CameraState{});
    EXPECT_EQ(frames, 1);
    EXPECT_EQ(cameras, 2);
    EXPECT_EQ(work, 0);
    EXPECT_EQ(bus.subscriber_count(CameraState::kind), 1u);
    EXPECT_EQ(bus.subscriber_count(plugin_msgs::BackgroundWork::kind), 1u);
    EXPECT_EQ(bus.subscriber_count("no_such_kind"), 0u);
}

TEST(MessageBus, HandlerRemovedByAnotherDuringDeliveryIsNotCalled) {
    engine::MessageBus bus;
    int second_calls = 0;
    engine::Subscription second;
    auto first = bus.subscribe<plugin_msgs::CameraState>([&](const plugin_msgs::CameraState&) { second.reset(); });
    second = bus.subscribe<plugin_msgs::CameraState>([&](const plugin_msgs::CameraState&) { ++second_calls; });
    bus.publish(plugin_msgs::CameraState{});
    EXPECT_EQ(second_calls, 0);
    EXPECT_EQ(bus.subscriber_count(plugin_msgs::CameraState::kind), 1u);
}
