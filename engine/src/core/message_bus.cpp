#include "engine/core/message_bus.h"

#include <algorithm>

namespace engine {

void Subscription::reset() {
    if (bus_ != nullptr) bus_->remove(kind_, id_);
    bus_ = nullptr;
}

std::uint64_t MessageBus::add(std::string kind, Handler handler) {
    std::lock_guard lock(mutex_);
    const std::uint64_t id = next_id_++;
    auto entry = std::make_shared<Entry>();
    entry->handler = std::move(handler);
    handlers_[std::move(kind)].emplace_back(id, std::move(entry));
    return id;
}

void MessageBus::remove(const std::string& kind, std::uint64_t id) {
    std::lock_guard lock(mutex_);
    auto it = handlers_.find(kind);
    if (it == handlers_.end()) return;
    std::erase_if(it->second, [id](const auto& entry) {
        if (entry.first != id) return false;
        entry.second->active = false;
        return true;
    });
}

void MessageBus::deliver(const std::string& kind, std::any message) {
    std::vector<std::shared_ptr<Entry>> targets;
    {
        std::lock_guard lock(mutex_);
        latest_[kind] = message;
        if (auto it = handlers_.find(kind); it != handlers_.end())
            for (const auto& entry : it->second) targets.push_back(entry.second);
    }
    // Called outside the lock so that handlers may publish or (un)subscribe.
    for (const auto& entry : targets)
        if (entry->active) entry->handler(message);
}

std::size_t MessageBus::subscriber_count(std::string_view kind) const {
    std::lock_guard lock(mutex_);
    const auto it = handlers_.find(std::string(kind));
    return it == handlers_.end() ? 0 : it->second.size();
}

}  // namespace engine
