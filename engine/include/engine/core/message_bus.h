#pragma once
// A typed publish/subscribe bus. Message types are plain structs with a
// `static constexpr std::string_view kind` (see plugin_msgs/), which keys them safely across
// shared-library boundaries. Delivery is synchronous, on the publishing thread, in subscription
// order; the bus also keeps the latest message of each kind for late readers (UI, tests).
#include <any>
#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace engine {

class MessageBus;

// Unsubscribes when destroyed; move-only.
class Subscription {
public:
    Subscription() = default;
    Subscription(MessageBus* bus, std::string kind, std::uint64_t id) : bus_(bus), kind_(std::move(kind)), id_(id) {}
    ~Subscription() { reset(); }
    Subscription(Subscription&& o) noexcept
        : bus_(std::exchange(o.bus_, nullptr)), kind_(std::move(o.kind_)), id_(o.id_) {}
    Subscription& operator=(Subscription&& o) noexcept {
        if (this != &o) {
            reset();
            bus_ = std::exchange(o.bus_, nullptr);
            kind_ = std::move(o.kind_);
            id_ = o.id_;
        }
        return *this;
    }
    Subscription(const Subscription&) = delete;
    Subscription& operator=(const Subscription&) = delete;
    void reset();

private:
    MessageBus* bus_ = nullptr;
    std::string kind_;
    std::uint64_t id_ = 0;
};

class MessageBus {
public:
    template <class M>
    [[nodiscard]] Subscription subscribe(std::function<void(const M&)> handler) {
        auto erased = [h = std::move(handler)](const std::any& message) { h(std::any_cast<const M&>(message)); };
        return Subscription(this, std::string(M::kind), add(std::string(M::kind), std::move(erased)));
    }

    template <class M>
    void publish(const M& message) {
        deliver(std::string(M::kind), std::any(message));
    }

    // The last message of this kind published, if any.
    template <class M>
    std::optional<M> latest() const {
        std::lock_guard lock(mutex_);
        const auto it = latest_.find(std::string(M::kind));
        if (it == latest_.end()) return std::nullopt;
        return std::any_cast<M>(it->second);
    }

    std::size_t subscriber_count(std::string_view kind) const;

private:
    friend class Subscription;
    using Handler = std::function<void(const std::any&)>;
    // `active` turns false on unsubscribe, so a handler removed during a delivery (by another
    // handler) is not called for the rest of it.
    struct Entry {
        Handler handler;
        std::atomic<bool> active{true};
    };
    std::uint64_t add(std::string kind, Handler handler);
    void remove(const std::string& kind, std::uint64_t id);
    void deliver(const std::string& kind, std::any message);

    mutable std::mutex mutex_;
    std::uint64_t next_id_ = 1;
    std::map<std::string, std::vector<std::pair<std::uint64_t, std::shared_ptr<Entry>>>> handlers_;
    std::map<std::string, std::any> latest_;
};

}  // namespace engine
