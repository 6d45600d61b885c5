/* The wavefront's stages and the queues between them, declared once. Each
 * stage is one kernel, defined in kernels/<stage>.cl, run over the queue it
 * consumes; it pushes each path it keeps to the queues of the stages that
 * take it next. An iteration runs the stages in this list's order.
 *
 * The list expands, on the host (src/wavefront/stage.h), into the Stage enum,
 * the table of kernels and queues, the program's stage files, the order of an
 * iteration, the queue bookkeeping between stages (QueueSet, derived in
 * src/wavefront/queue_plan.cpp) and the profiler's items per stage; in the
 * kernels (device/path_queues.h), into each stage's queues, which its kernel
 * restates in its first line (STAGE_QUEUES) and against which every push is
 * checked when the kernel compiles (STAGE_PUSH). Adding a stage is one line
 * here and its kernel file.
 *
 * X(stage, loop, consumes, pushes to, runs when, traces), where
 *   loop       the loop of iterations the stage belongs to: CAMERA (the
 *              paths from the camera) or PHOTON (SPPM's photon pass, which
 *              runs once the camera pass of its iteration has drained);
 *   consumes   a queue of interface/queues.h, by name (WP_QUEUE_<name>);
 *   pushes to  WP_PUSHES(queue, ...), the queues it may push to, or
 *              WP_PUSHES_NOTHING;
 *   runs when  a path state feature (interface/path_state.h): ALWAYS,
 *              SHADOW_STAGE for the stage of next-event estimation's
 *              shadow rays (which shade traces itself where the device
 *              traces on a CPU: see below), HIT_STAGE for intersect and
 *              shade apart and INTERSECT_AND_SHADE for them as one
 *              kernel (see below), SPPM for one that only the sppm
 *              integrator needs;
 *   traces     the rays of the paths it consumes: CLOSEST_HIT (their
 *              extension rays, into hit_t and hit_shape), ANY_HIT (their
 *              shadow rays, blocked or not) or NO_RAYS. Where the host
 *              traces (--intersector embree, src/wavefront/host_trace.h),
 *              it traces a stage's queue before the stage's kernel, built
 *              with WP_HOST_TRACED, reads the results and does the rest.
 *              The photon stages trace on the device (sppm takes the BVH),
 *              so intersect_photons, which traces closest hits, is NO_RAYS
 *              here: there is nothing for the host to trace before it.
 *
 * Shadow rays: on a CPU device that traces them itself, shade traces its
 * vertices' shadow rays at once (one kernel fewer, the shadow rays' state
 * neither written nor read again; measured in docs/architecture.md, "Shadow
 * rays") and pushes them to SHADOW only to count them (--profile's
 * rays by depth, the summary's shadow rays); no stage consumes them. Where
 * the host traces them, and on GPUs, intersect_shadow does (SHADOW_STAGE).
 *
 * Hits: on a CPU device, intersect_and_shade traces each extension ray and
 * shades its hit in one kernel (INTERSECT_AND_SHADE): the hits stay in
 * registers, with no launch, compaction or hit_t/hit_shape traffic between
 * the two (docs/architecture.md, "Intersect and shade as one kernel"). It
 * pushes the paths that go on to RAY, the queue it takes, which only scan
 * compaction can build while the stage reads it, so with atomic compaction,
 * and on GPUs, intersect and shade run apart, the hits going through HIT
 * (HIT_STAGE). Two stages consume RAY, never in one program. */
#ifndef WP_INTERFACE_STAGES_H
#define WP_INTERFACE_STAGES_H

#include "interface/queues.h"

#define WP_STAGES(X)                                                                                    \
    X(generate, CAMERA, FREE, WP_PUSHES(RAY), ALWAYS, NO_RAYS)                                          \
    X(intersect, CAMERA, RAY, WP_PUSHES(HIT), HIT_STAGE, CLOSEST_HIT)                                   \
    X(shade, CAMERA, HIT, WP_PUSHES(SHADOW, RAY, FREE), HIT_STAGE, NO_RAYS)                             \
    X(intersect_and_shade, CAMERA, RAY, WP_PUSHES(SHADOW, RAY, FREE), INTERSECT_AND_SHADE, CLOSEST_HIT) \
    X(intersect_shadow, CAMERA, SHADOW, WP_PUSHES_NOTHING, SHADOW_STAGE, ANY_HIT)                       \
    X(emit_photons, PHOTON, PHOTON_FREE, WP_PUSHES(PHOTON_RAY), SPPM, NO_RAYS)                          \
    X(intersect_photons, PHOTON, PHOTON_RAY, WP_PUSHES(PHOTON_HIT, PHOTON_FREE), SPPM, NO_RAYS)         \
    X(shade_photons, PHOTON, PHOTON_HIT, WP_PUSHES(PHOTON_RAY, PHOTON_FREE), SPPM, NO_RAYS)

/* A set of queues as bits 1 << queue, from one to five queue names. */
#define WP_QUEUE_BIT(queue) (1u << WP_QUEUE_##queue)
#define WP_PUSHES_1(a) WP_QUEUE_BIT(a)
#define WP_PUSHES_2(a, b) (WP_QUEUE_BIT(a) | WP_QUEUE_BIT(b))
#define WP_PUSHES_3(a, b, c) (WP_PUSHES_2(a, b) | WP_QUEUE_BIT(c))
#define WP_PUSHES_4(a, b, c, d) (WP_PUSHES_3(a, b, c) | WP_QUEUE_BIT(d))
#define WP_PUSHES_5(a, b, c, d, e) (WP_PUSHES_4(a, b, c, d) | WP_QUEUE_BIT(e))
#define WP_PUSHES_CHOOSE(a, b, c, d, e, chosen, ...) chosen
#define WP_PUSHES(...) \
    WP_PUSHES_CHOOSE(__VA_ARGS__, WP_PUSHES_5, WP_PUSHES_4, WP_PUSHES_3, WP_PUSHES_2, WP_PUSHES_1, )(__VA_ARGS__)
#define WP_PUSHES_NOTHING 0u

#endif
