#pragma once
// Result<T>: a value or one error line for the user ("FILE: what is wrong").
// Expected failures (missing files, corrupt data, bad parameters) travel as Result; the
// command line prints the message and exits non-zero.
//
//   Result<Image> img = loadImage("a.png");
//   if (!img) return Error{img.error()};
//   use(*img);

#include <string>
#include <utility>
#include <variant>

#include "core/check.h"

namespace btflut {

struct Error {
    std::string message;
};

template <typename T>
class [[nodiscard]] Result {
public:
    Result(T value) : m_state(std::move(value)) {}
    Result(Error error) : m_state(std::move(error)) {}

    bool ok() const { return std::holds_alternative<T>(m_state); }
    explicit operator bool() const { return ok(); }

    T& value() & {
        BTFLUT_CHECK(ok());
        return std::get<T>(m_state);
    }
    const T& value() const& {
        BTFLUT_CHECK(ok());
        return std::get<T>(m_state);
    }
    T&& value() && {
        BTFLUT_CHECK(ok());
        return std::get<T>(std::move(m_state));
    }
    T& operator*() & { return value(); }
    const T& operator*() const& { return value(); }
    T&& operator*() && { return std::move(*this).value(); }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }

    const std::string& error() const {
        BTFLUT_CHECK(!ok());
        return std::get<Error>(m_state).message;
    }

private:
    std::variant<T, Error> m_state;
};

/// Result of an operation that produces nothing but may fail.
struct Done {};
using Status = Result<Done>;
inline Status success() { return Done{}; }

}  // namespace btflut
