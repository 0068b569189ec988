#include "cli/bench_timing.h"

#include <chrono>
#include <vector>

#include "gl/context.h"
#include "gl/objects.h"

namespace btflut {

Result<DrawTimes> timeDraws(int count, bool timer, const std::function<Status()>& draw) {
    std::vector<GlQuery> queries;
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < count; ++k) {
        if (timer) {
            queries.push_back(makeQuery());
            gl.BeginQuery(GL_TIME_ELAPSED, queries.back().id());
        }
        if (Status s = draw(); !s) return Error{s.error()};
        if (timer) gl.EndQuery(GL_TIME_ELAPSED);
    }
    gl.Finish();
    DrawTimes t;
    t.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / count;
    if (timer) {
        GLuint64 total = 0;
        for (const GlQuery& q : queries) {
            GLuint64 ns = 0;
            gl.GetQueryObjectui64v(q.id(), GL_QUERY_RESULT, &ns);
            total += ns;
        }
        t.gpu = static_cast<double>(total) * 1e-9 / count;
    }
    return t;
}

}  // namespace btflut
