#pragma once
// Helpers for tests of typed messages (plugin_msgs and the plugins' own): a JSON round trip, and
// bad input rejected with std::invalid_argument naming the kind and key.
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace engine::test {

// to_json → text → parse → from_json must give back the original.
template <class M>
void expect_round_trip(const M& original) {
    const std::string text = nlohmann::json(original).dump();
    const M back = nlohmann::json::parse(text).get<M>();
    EXPECT_EQ(back, original) << text;
}

// The message of the std::invalid_argument that parsing `text` as M throws; empty when it parses.
template <class M>
std::string parse_error(const std::string& text) {
    try {
        nlohmann::json::parse(text).get<M>();
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

struct Rejection {
    std::string text;
    std::string named;  // what the message must contain: the kind and the key
};

template <class M>
void expect_rejected(const std::vector<Rejection>& cases) {
    for (const auto& c : cases) {
        SCOPED_TRACE(c.text);
        const std::string error = parse_error<M>(c.text);
        EXPECT_NE(error.find(c.named), std::string::npos) << "message: '" << error << "'";
    }
}

}  // namespace engine::test
