// glsl/trace/queue_args.glsl: the indirect dispatch arguments of the next
// stages, computed by the last work group to finish the stage that filled
// their queues (a ticket counter says which group that is). A one-invocation
// dispatch of its own between the stages did this before, and paid a
// dispatch's launch and drain three times per iteration for one
// invocation's work (bench/RESULTS.md, "Figures behind the code").
// Include after common.glsl.
#ifndef CV_TRACE_QUEUE_ARGS_GLSL
#define CV_TRACE_QUEUE_ARGS_GLSL

// Groups for n items, split over y past 65535. Never 0 groups: a stage whose
// last group prepares the next stages must run even with nothing to do.
uvec4 cv_groups(uint n)
{
    uint g = max((n + uint(CV_TRACE_GROUP) - 1u) / uint(CV_TRACE_GROUP), 1u);
    uint gy = 1u;
    if (g > 65535u) {
        gy = (g + 65534u) / 65535u;
        g = (g + gy - 1u) / gy;
    }
    return uvec4(g, gy, 1u, 0u);
}

uint cv_groups_in(uvec4 args) { return args.x * args.y * args.z; }

void cv_stat_add(uint slot, uint n)
{
    uint lo = q.stats[slot].x + n;
    if (lo < n)
        q.stats[slot].y += 1u;
    q.stats[slot].x = lo;
}

// Whether the calling group is the last of `groups` to pass this point.
// Call from the invocation that took the group's queue slots
// (cv_queue_slot_taker), after that, so every group's pushes are counted
// before its ticket; the last group sets the ticket back to 0 for the next
// use.
bool cv_last_group(uint ticket, uint groups)
{
    memoryBarrierBuffer();
    if (atomicAdd(q.count[ticket], 1u) + 1u != groups)
        return false;
    memoryBarrierBuffer();
    q.count[ticket] = 0u;
    return true;
}

// A queue counter as the atomics left it (past any cached copy).
uint cv_count(uint slot) { return atomicAdd(q.count[slot], 0u); }

// The rays the next iteration traces: those written this iteration (bounce
// and camera rays); the other queues start empty but for the shadow rays,
// which the shadow stage has yet to read (the intersect stage empties it).
void cv_prepare_iteration(uint n)
{
    q.count[CV_Q_RAYS_IN] = n;
    q.count[CV_Q_RAYS_OUT] = 0u;
    q.count[CV_Q_HITS] = 0u;
    q.count[CV_Q_HITS_B] = 0u;
    q.count[CV_Q_HITS_C] = 0u;
    q.count[CV_Q_ESCAPED] = 0u;
    q.args[CV_ARGS_RAYS] = cv_groups(n);
    cv_stat_add(CV_STAT_EXTEND, n);
}

// After the intersect stage: the shade (and rlpath's escaped) dispatches.
void cv_prepare_shade()
{
    uint a = cv_count(CV_Q_HITS), b = cv_count(CV_Q_HITS_B), c = cv_count(CV_Q_HITS_C);
    q.args[CV_ARGS_HITS] = cv_groups(a);
    q.args[CV_ARGS_HITS_B] = cv_groups(b);
    q.args[CV_ARGS_HITS_C] = cv_groups(c);
    q.args[CV_ARGS_HITS_ALL] = cv_groups(a + b + c);
    q.args[CV_ARGS_ESCAPED] = cv_groups(cv_count(CV_Q_ESCAPED));
    q.count[CV_Q_SHADOW] = 0u;
    cv_stat_add(CV_STAT_HITS, a + b + c);
}

// After the shade stage: the shadow dispatch and the next iteration.
void cv_prepare_shadow()
{
    uint s = cv_count(CV_Q_SHADOW);
    q.args[CV_ARGS_SHADOW] = cv_groups(s);
    cv_stat_add(CV_STAT_SHADOW, s);
    cv_prepare_iteration(cv_count(CV_Q_RAYS_OUT));
}

#endif
