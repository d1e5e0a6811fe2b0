/* rt_vk.c: the RT-core back end of rt_probe (see rt_vk.h). Plain Vulkan
 * 1.2: buffers in device memory filled through a host-visible staging
 * buffer, one command buffer per step submitted and waited for (set-up and
 * timing only: nothing here is on a hot path). Each timed launch sits
 * alone between two timestamps of its own submission. */
#include "config.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <vulkan/vulkan.h>

#include "bench/rt_vk.h"
/* SPIR-V of bench/rt_probe.{rgen,rchit,rmiss}, made at build time */
#include "bench/rt_probe_rgen.h"
#include "bench/rt_probe_rchit.h"
#include "bench/rt_probe_rmiss.h"

struct vbuf {
    VkBuffer b;
    VkDeviceMemory m;
    VkDeviceSize size;
    VkDeviceAddress addr;
};

struct rt_vk {
    VkInstance inst;
    VkPhysicalDevice phys;
    VkDevice dev;
    VkQueue queue;
    uint32_t family;
    VkCommandPool pool;
    VkQueryPool timestamps;
    double tick_ns;
    uint64_t tick_mask;
    VkPhysicalDeviceMemoryProperties mem;
    VkPhysicalDeviceRayTracingPipelinePropertiesKHR rt;
    uint32_t max_launch_x;
    struct vbuf verts, index, blas_buf, tlas_buf, inst_buf, sbt;
    struct vbuf rays, results;  /* sized for the largest ray set so far */
    VkAccelerationStructureKHR blas, tlas;
    VkDescriptorSetLayout set_layout;
    VkDescriptorPool desc_pool;
    VkDescriptorSet set;
    VkPipelineLayout layout;
    VkPipeline pipeline;
    VkStridedDeviceAddressRegionKHR sbt_rgen, sbt_miss, sbt_hit, sbt_call;
    PFN_vkCreateAccelerationStructureKHR create_as;
    PFN_vkDestroyAccelerationStructureKHR destroy_as;
    PFN_vkGetAccelerationStructureBuildSizesKHR build_sizes;
    PFN_vkCmdBuildAccelerationStructuresKHR cmd_build_as;
    PFN_vkGetAccelerationStructureDeviceAddressKHR as_address;
    PFN_vkCreateRayTracingPipelinesKHR create_rt_pipelines;
    PFN_vkGetRayTracingShaderGroupHandlesKHR group_handles;
    PFN_vkCmdTraceRaysKHR cmd_trace_rays;
};

static bool vk_ok(VkResult r, const char *what, struct cv_error *err)
{
    if (r == VK_SUCCESS)
        return true;
    return cv_fail(err, "vulkan: %s: VkResult %d", what, (int)r);
}

static VkDeviceSize align_up(VkDeviceSize v, VkDeviceSize a)
{
    return a ? (v + a - 1) / a * a : v;
}

static bool mem_type(const struct rt_vk *v, uint32_t bits, VkMemoryPropertyFlags want,
                     uint32_t *out)
{
    for (uint32_t i = 0; i < v->mem.memoryTypeCount; i++)
        if ((bits & (1u << i)) && (v->mem.memoryTypes[i].propertyFlags & want) == want) {
            *out = i;
            return true;
        }
    return false;
}

/* A buffer of `size` bytes with its own memory; device addresses when the
 * usage asks for them. */
static bool buf_create(struct rt_vk *v, VkDeviceSize size, VkBufferUsageFlags usage,
                       VkMemoryPropertyFlags props, struct vbuf *b, const char *what,
                       struct cv_error *err)
{
    memset(b, 0, sizeof(*b));
    b->size = size ? size : 16;
    VkBufferCreateInfo bi = {.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO,
                             .size = b->size,
                             .usage = usage,
                             .sharingMode = VK_SHARING_MODE_EXCLUSIVE};
    if (!vk_ok(vkCreateBuffer(v->dev, &bi, NULL, &b->b), what, err))
        return false;
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(v->dev, b->b, &req);
    uint32_t type;
    if (!mem_type(v, req.memoryTypeBits, props, &type))
        return cv_fail(err, "vulkan: %s: no memory type with flags 0x%x", what, (unsigned)props);
    bool addr = (usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) != 0;
    VkMemoryAllocateFlagsInfo fi = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO,
                                    .flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT};
    VkMemoryAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                               .pNext = addr ? &fi : NULL,
                               .allocationSize = req.size,
                               .memoryTypeIndex = type};
    if (!vk_ok(vkAllocateMemory(v->dev, &ai, NULL, &b->m), what, err) ||
        !vk_ok(vkBindBufferMemory(v->dev, b->b, b->m, 0), what, err))
        return false;
    if (addr) {
        VkBufferDeviceAddressInfo di = {.sType = VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO,
                                        .buffer = b->b};
        b->addr = vkGetBufferDeviceAddress(v->dev, &di);
    }
    return true;
}

static void buf_destroy(struct rt_vk *v, struct vbuf *b)
{
    if (b->b)
        vkDestroyBuffer(v->dev, b->b, NULL);
    if (b->m)
        vkFreeMemory(v->dev, b->m, NULL);
    memset(b, 0, sizeof(*b));
}

static bool cmd_begin(struct rt_vk *v, VkCommandBuffer *cb, struct cv_error *err)
{
    VkCommandBufferAllocateInfo ai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                      .commandPool = v->pool,
                                      .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                      .commandBufferCount = 1};
    if (!vk_ok(vkAllocateCommandBuffers(v->dev, &ai, cb), "allocating a command buffer", err))
        return false;
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO,
                                   .flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT};
    if (!vk_ok(vkBeginCommandBuffer(*cb, &bi), "beginning a command buffer", err))
        return false;
    /* the previous submission's writes (uploads, builds) visible to this
     * one's reads: waiting for the queue alone does not make them so */
    VkMemoryBarrier mb = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                          .srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT,
                          .dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT};
    vkCmdPipelineBarrier(*cb, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                         VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &mb, 0, NULL, 0, NULL);
    return true;
}

/* Submits cb, waits for it and frees it. */
static bool cmd_run(struct rt_vk *v, VkCommandBuffer cb, const char *what, struct cv_error *err)
{
    bool ok = vk_ok(vkEndCommandBuffer(cb), what, err);
    VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
                       .commandBufferCount = 1,
                       .pCommandBuffers = &cb};
    ok = ok && vk_ok(vkQueueSubmit(v->queue, 1, &si, VK_NULL_HANDLE), what, err) &&
         vk_ok(vkQueueWaitIdle(v->queue), what, err);
    vkFreeCommandBuffers(v->dev, v->pool, 1, &cb);
    return ok;
}

/* The GPU time between timestamps 0 and 1 [ms]. */
static bool read_ms(struct rt_vk *v, double *ms, struct cv_error *err)
{
    uint64_t t[2];
    if (!vk_ok(vkGetQueryPoolResults(v->dev, v->timestamps, 0, 2, sizeof(t), t, sizeof(t[0]),
                                     VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
               "reading timestamps", err))
        return false;
    *ms = (double)((t[1] - t[0]) & v->tick_mask) * v->tick_ns * 1e-6;
    return true;
}

/* Copies between a device buffer and host memory through a staging buffer. */
static bool transfer(struct rt_vk *v, struct vbuf *dst, const void *src, void *out,
                     VkDeviceSize bytes, struct cv_error *err)
{
    struct vbuf st;
    const VkMemoryPropertyFlags host =
        VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    if (!buf_create(v, bytes,
                    VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, host,
                    &st, "staging buffer", err))
        return false;
    void *map = NULL;
    bool ok = vk_ok(vkMapMemory(v->dev, st.m, 0, bytes, 0, &map), "mapping staging", err);
    if (ok && src)
        memcpy(map, src, bytes);
    VkCommandBuffer cb;
    if (ok && (ok = cmd_begin(v, &cb, err))) {
        VkBufferCopy c = {.size = bytes};
        if (src)
            vkCmdCopyBuffer(cb, st.b, dst->b, 1, &c);
        else
            vkCmdCopyBuffer(cb, dst->b, st.b, 1, &c);
        ok = cmd_run(v, cb, "copying a buffer", err);
    }
    if (ok && out)
        memcpy(out, map, bytes);
    if (map)
        vkUnmapMemory(v->dev, st.m);
    buf_destroy(v, &st);
    return ok;
}

static bool has_ext(const VkExtensionProperties *e, uint32_t n, const char *name)
{
    for (uint32_t i = 0; i < n; i++)
        if (!strcmp(e[i].extensionName, name))
            return true;
    return false;
}

static const char *const device_exts[] = {
    VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME,
    VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME,
    VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME,
};
#define N_DEVICE_EXTS (sizeof(device_exts) / sizeof(device_exts[0]))

/* The first device with ray-tracing pipelines, a queue family that computes
 * and writes timestamps; its name and the others' in err when none. */
static bool pick_device(struct rt_vk *v, struct cv_error *err)
{
    uint32_t n = 0;
    vkEnumeratePhysicalDevices(v->inst, &n, NULL);
    VkPhysicalDevice *pd = calloc(n + 1, sizeof(*pd));
    vkEnumeratePhysicalDevices(v->inst, &n, pd);
    char seen[512] = "";
    for (uint32_t i = 0; i < n && !v->phys; i++) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(pd[i], &p);
        size_t len = strlen(seen);
        snprintf(seen + len, sizeof(seen) - len, "%s%s", len ? ", " : "", p.deviceName);
        uint32_t ne = 0;
        vkEnumerateDeviceExtensionProperties(pd[i], NULL, &ne, NULL);
        VkExtensionProperties *e = calloc(ne + 1, sizeof(*e));
        vkEnumerateDeviceExtensionProperties(pd[i], NULL, &ne, e);
        bool all = p.apiVersion >= VK_API_VERSION_1_2;
        for (size_t k = 0; k < N_DEVICE_EXTS; k++)
            all = all && has_ext(e, ne, device_exts[k]);
        free(e);
        if (!all)
            continue;
        uint32_t nf = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(pd[i], &nf, NULL);
        VkQueueFamilyProperties *qf = calloc(nf + 1, sizeof(*qf));
        vkGetPhysicalDeviceQueueFamilyProperties(pd[i], &nf, qf);
        for (uint32_t f = 0; f < nf; f++)
            if ((qf[f].queueFlags & VK_QUEUE_COMPUTE_BIT) && qf[f].timestampValidBits > 0) {
                v->phys = pd[i];
                v->family = f;
                v->tick_mask = qf[f].timestampValidBits >= 64
                                   ? ~0ull
                                   : (1ull << qf[f].timestampValidBits) - 1;
                break;
            }
        free(qf);
    }
    free(pd);
    if (!v->phys)
        return cv_fail(err, "vulkan: no device with %s and %s (devices: %s)", device_exts[0],
                       device_exts[1], n ? seen : "none");
    return true;
}

static bool make_device(struct rt_vk *v, struct rt_vk_info *info, struct cv_error *err)
{
    VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                             .pApplicationName = "rt_probe",
                             .apiVersion = VK_API_VERSION_1_2};
    VkInstanceCreateInfo ii = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
                               .pApplicationInfo = &app};
    if (!vk_ok(vkCreateInstance(&ii, NULL, &v->inst), "creating the instance", err) ||
        !pick_device(v, err))
        return false;
    VkPhysicalDeviceDriverProperties drv = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
    v->rt = (VkPhysicalDeviceRayTracingPipelinePropertiesKHR){
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_PROPERTIES_KHR,
        .pNext = &drv};
    VkPhysicalDeviceProperties2 p2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2,
                                      .pNext = &v->rt};
    vkGetPhysicalDeviceProperties2(v->phys, &p2);
    snprintf(info->device, sizeof(info->device), "%s", p2.properties.deviceName);
    snprintf(info->driver, sizeof(info->driver), "%s %s", drv.driverName, drv.driverInfo);
    v->tick_ns = p2.properties.limits.timestampPeriod;
    uint64_t lx = (uint64_t)p2.properties.limits.maxComputeWorkGroupCount[0] *
                  p2.properties.limits.maxComputeWorkGroupSize[0];
    v->max_launch_x = lx > (1u << 30) ? (1u << 30) : (uint32_t)lx;
    vkGetPhysicalDeviceMemoryProperties(v->phys, &v->mem);

    VkPhysicalDeviceRayTracingPipelineFeaturesKHR rtf = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR,
        .rayTracingPipeline = VK_TRUE};
    VkPhysicalDeviceAccelerationStructureFeaturesKHR asf = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR,
        .pNext = &rtf,
        .accelerationStructure = VK_TRUE};
    VkPhysicalDeviceVulkan12Features f12 = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES,
        .pNext = &asf,
        .bufferDeviceAddress = VK_TRUE};
    float prio = 1.0f;
    VkDeviceQueueCreateInfo qi = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                  .queueFamilyIndex = v->family,
                                  .queueCount = 1,
                                  .pQueuePriorities = &prio};
    VkDeviceCreateInfo di = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
                             .pNext = &f12,
                             .queueCreateInfoCount = 1,
                             .pQueueCreateInfos = &qi,
                             .enabledExtensionCount = N_DEVICE_EXTS,
                             .ppEnabledExtensionNames = device_exts};
    if (!vk_ok(vkCreateDevice(v->phys, &di, NULL, &v->dev), "creating the device", err))
        return false;
    vkGetDeviceQueue(v->dev, v->family, 0, &v->queue);
#define LOAD(field, name)                                                               \
    if (!(v->field = (PFN_##name)vkGetDeviceProcAddr(v->dev, #name)))                    \
        return cv_fail(err, "vulkan: %s missing", #name);
    LOAD(create_as, vkCreateAccelerationStructureKHR);
    LOAD(destroy_as, vkDestroyAccelerationStructureKHR);
    LOAD(build_sizes, vkGetAccelerationStructureBuildSizesKHR);
    LOAD(cmd_build_as, vkCmdBuildAccelerationStructuresKHR);
    LOAD(as_address, vkGetAccelerationStructureDeviceAddressKHR);
    LOAD(create_rt_pipelines, vkCreateRayTracingPipelinesKHR);
    LOAD(group_handles, vkGetRayTracingShaderGroupHandlesKHR);
    LOAD(cmd_trace_rays, vkCmdTraceRaysKHR);
#undef LOAD
    VkCommandPoolCreateInfo pi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                  .queueFamilyIndex = v->family};
    VkQueryPoolCreateInfo qpi = {.sType = VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO,
                                 .queryType = VK_QUERY_TYPE_TIMESTAMP,
                                 .queryCount = 2};
    return vk_ok(vkCreateCommandPool(v->dev, &pi, NULL, &v->pool), "command pool", err) &&
           vk_ok(vkCreateQueryPool(v->dev, &qpi, NULL, &v->timestamps), "query pool", err);
}

/* Builds one acceleration structure (geometry g, prims primitives) into a
 * buffer of its own, timed. */
static bool build_as(struct rt_vk *v, VkAccelerationStructureTypeKHR type,
                     const VkAccelerationStructureGeometryKHR *g, uint32_t prims,
                     struct vbuf *store, VkAccelerationStructureKHR *as, double *ms,
                     struct cv_error *err)
{
    VkAccelerationStructureBuildGeometryInfoKHR bi = {
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR,
        .type = type,
        .flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR,
        .mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR,
        .geometryCount = 1,
        .pGeometries = g};
    VkAccelerationStructureBuildSizesInfoKHR sz = {
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    v->build_sizes(v->dev, VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &bi, &prims, &sz);
    const VkMemoryPropertyFlags local = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    if (!buf_create(v, sz.accelerationStructureSize,
                    VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR |
                        VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                    local, store, "acceleration structure", err))
        return false;
    VkAccelerationStructureCreateInfoKHR ci = {
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR,
        .buffer = store->b,
        .size = sz.accelerationStructureSize,
        .type = type};
    if (!vk_ok(v->create_as(v->dev, &ci, NULL, as), "creating an acceleration structure", err))
        return false;
    /* scratch: its address aligned as the device asks */
    VkPhysicalDeviceAccelerationStructurePropertiesKHR ap = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
    VkPhysicalDeviceProperties2 p2 = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2,
                                      .pNext = &ap};
    vkGetPhysicalDeviceProperties2(v->phys, &p2);
    VkDeviceSize al = ap.minAccelerationStructureScratchOffsetAlignment;
    struct vbuf scratch;
    if (!buf_create(v, sz.buildScratchSize + al,
                    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT,
                    local, &scratch, "scratch", err))
        return false;
    bi.dstAccelerationStructure = *as;
    bi.scratchData.deviceAddress = align_up(scratch.addr, al);
    VkAccelerationStructureBuildRangeInfoKHR range = {.primitiveCount = prims};
    const VkAccelerationStructureBuildRangeInfoKHR *ranges = &range;
    VkCommandBuffer cb;
    bool ok = cmd_begin(v, &cb, err);
    if (ok) {
        vkCmdResetQueryPool(cb, v->timestamps, 0, 2);
        vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, v->timestamps, 0);
        v->cmd_build_as(cb, 1, &bi, &ranges);
        vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, v->timestamps, 1);
        ok = cmd_run(v, cb, "building an acceleration structure", err) && read_ms(v, ms, err);
    }
    buf_destroy(v, &scratch);
    return ok;
}

static bool make_structures(struct rt_vk *v, const void *vertices, uint32_t stride,
                            uint32_t n_vertices, const uint32_t *idx, uint32_t n_tris,
                            struct rt_vk_info *info, struct cv_error *err)
{
    const VkBufferUsageFlags geo = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR |
                                   VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    const VkMemoryPropertyFlags local = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
    VkDeviceSize vb = (VkDeviceSize)n_vertices * stride, ib = (VkDeviceSize)n_tris * 12;
    if (!buf_create(v, vb, geo, local, &v->verts, "vertices", err) ||
        !buf_create(v, ib, geo, local, &v->index, "indices", err) ||
        !transfer(v, &v->verts, vertices, NULL, vb, err) || !transfer(v, &v->index, idx, NULL, ib, err))
        return false;
    VkAccelerationStructureGeometryKHR tg = {
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR,
        .geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR,
        .flags = VK_GEOMETRY_OPAQUE_BIT_KHR,
        .geometry.triangles = {
            .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR,
            .vertexFormat = VK_FORMAT_R32G32B32_SFLOAT,
            .vertexData.deviceAddress = v->verts.addr,
            .vertexStride = stride,
            .maxVertex = n_vertices ? n_vertices - 1 : 0,
            .indexType = VK_INDEX_TYPE_UINT32,
            .indexData.deviceAddress = v->index.addr}};
    if (!build_as(v, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, &tg, n_tris, &v->blas_buf,
                  &v->blas, &info->blas_ms, err))
        return false;
    info->blas_mb = (double)v->blas_buf.size / (1024.0 * 1024.0);
    VkAccelerationStructureDeviceAddressInfoKHR ai = {
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR,
        .accelerationStructure = v->blas};
    VkAccelerationStructureInstanceKHR inst = {
        .transform.matrix = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}},
        .mask = 0xff,
        .flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR,
        .accelerationStructureReference = v->as_address(v->dev, &ai)};
    if (!buf_create(v, sizeof(inst), geo, local, &v->inst_buf, "instances", err) ||
        !transfer(v, &v->inst_buf, &inst, NULL, sizeof(inst), err))
        return false;
    VkAccelerationStructureGeometryKHR ig = {
        .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR,
        .geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR,
        .flags = VK_GEOMETRY_OPAQUE_BIT_KHR,
        .geometry.instances = {
            .sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR,
            .data.deviceAddress = v->inst_buf.addr}};
    return build_as(v, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, &ig, 1, &v->tlas_buf,
                    &v->tlas, &info->tlas_ms, err);
}

static bool shader_module(struct rt_vk *v, const uint32_t *code, size_t bytes, VkShaderModule *m,
                          struct cv_error *err)
{
    VkShaderModuleCreateInfo ci = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
                                   .codeSize = bytes,
                                   .pCode = code};
    return vk_ok(vkCreateShaderModule(v->dev, &ci, NULL, m), "shader module", err);
}

/* The pipeline (raygen, miss, one triangle hit group), its layout and its
 * shader binding table. */
static bool make_pipeline(struct rt_vk *v, struct cv_error *err)
{
    VkDescriptorSetLayoutBinding b[3] = {
        {0, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR, 1, VK_SHADER_STAGE_RAYGEN_BIT_KHR, NULL},
        {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_RAYGEN_BIT_KHR, NULL},
        {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_RAYGEN_BIT_KHR, NULL}};
    VkDescriptorSetLayoutCreateInfo li = {
        .sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
        .bindingCount = 3,
        .pBindings = b};
    VkPushConstantRange pcr = {VK_SHADER_STAGE_RAYGEN_BIT_KHR, 0, 8};
    if (!vk_ok(vkCreateDescriptorSetLayout(v->dev, &li, NULL, &v->set_layout), "set layout", err))
        return false;
    VkPipelineLayoutCreateInfo pli = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                      .setLayoutCount = 1,
                                      .pSetLayouts = &v->set_layout,
                                      .pushConstantRangeCount = 1,
                                      .pPushConstantRanges = &pcr};
    if (!vk_ok(vkCreatePipelineLayout(v->dev, &pli, NULL, &v->layout), "pipeline layout", err))
        return false;
    VkDescriptorPoolSize ps[2] = {{VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR, 1},
                                  {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2}};
    VkDescriptorPoolCreateInfo dpi = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                      .maxSets = 1,
                                      .poolSizeCount = 2,
                                      .pPoolSizes = ps};
    VkDescriptorSetAllocateInfo dsi = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                       .descriptorSetCount = 1,
                                       .pSetLayouts = &v->set_layout};
    if (!vk_ok(vkCreateDescriptorPool(v->dev, &dpi, NULL, &v->desc_pool), "descriptor pool", err))
        return false;
    dsi.descriptorPool = v->desc_pool;
    if (!vk_ok(vkAllocateDescriptorSets(v->dev, &dsi, &v->set), "descriptor set", err))
        return false;

    VkShaderModule mod[3] = {0};
    bool ok = shader_module(v, rt_probe_rgen, sizeof(rt_probe_rgen), &mod[0], err) &&
              shader_module(v, rt_probe_rmiss, sizeof(rt_probe_rmiss), &mod[1], err) &&
              shader_module(v, rt_probe_rchit, sizeof(rt_probe_rchit), &mod[2], err);
    if (ok) {
        const VkShaderStageFlagBits stage[3] = {VK_SHADER_STAGE_RAYGEN_BIT_KHR,
                                                VK_SHADER_STAGE_MISS_BIT_KHR,
                                                VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR};
        VkPipelineShaderStageCreateInfo st[3];
        VkRayTracingShaderGroupCreateInfoKHR g[3];
        for (int i = 0; i < 3; i++) {
            st[i] = (VkPipelineShaderStageCreateInfo){
                .sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                .stage = stage[i],
                .module = mod[i],
                .pName = "main"};
            g[i] = (VkRayTracingShaderGroupCreateInfoKHR){
                .sType = VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR,
                .type = i < 2 ? VK_RAY_TRACING_SHADER_GROUP_TYPE_GENERAL_KHR
                              : VK_RAY_TRACING_SHADER_GROUP_TYPE_TRIANGLES_HIT_GROUP_KHR,
                .generalShader = i < 2 ? (uint32_t)i : VK_SHADER_UNUSED_KHR,
                .closestHitShader = i == 2 ? 2u : VK_SHADER_UNUSED_KHR,
                .anyHitShader = VK_SHADER_UNUSED_KHR,
                .intersectionShader = VK_SHADER_UNUSED_KHR};
        }
        VkRayTracingPipelineCreateInfoKHR pi = {
            .sType = VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR,
            .stageCount = 3,
            .pStages = st,
            .groupCount = 3,
            .pGroups = g,
            .maxPipelineRayRecursionDepth = 1,
            .layout = v->layout};
        ok = vk_ok(v->create_rt_pipelines(v->dev, VK_NULL_HANDLE, VK_NULL_HANDLE, 1, &pi, NULL,
                                          &v->pipeline),
                   "creating the ray-tracing pipeline", err);
    }
    for (int i = 0; i < 3; i++)
        if (mod[i])
            vkDestroyShaderModule(v->dev, mod[i], NULL);
    if (!ok)
        return false;

    /* the table: raygen, miss, hit group, each region on the base alignment */
    VkDeviceSize hs = v->rt.shaderGroupHandleSize;
    VkDeviceSize rec = align_up(hs, v->rt.shaderGroupHandleAlignment);
    VkDeviceSize region = align_up(rec, v->rt.shaderGroupBaseAlignment);
    VkDeviceSize base = v->rt.shaderGroupBaseAlignment;
    uint8_t handles[3 * 64];
    if (hs > 64)
        return cv_fail(err, "vulkan: shader group handles of %u bytes", (unsigned)hs);
    if (!vk_ok(v->group_handles(v->dev, v->pipeline, 0, 3, 3 * hs, handles), "group handles",
               err) ||
        !buf_create(v, 3 * region + base,
                    VK_BUFFER_USAGE_SHADER_BINDING_TABLE_BIT_KHR |
                        VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                        VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                    VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, &v->sbt, "shader binding table", err))
        return false;
    VkDeviceAddress start = align_up(v->sbt.addr, base);
    VkDeviceSize off = start - v->sbt.addr;
    uint8_t *table = calloc(1, (size_t)v->sbt.size);
    for (int i = 0; i < 3; i++)
        memcpy(table + off + (VkDeviceSize)i * region, handles + (VkDeviceSize)i * hs, hs);
    ok = transfer(v, &v->sbt, table, NULL, v->sbt.size, err);
    free(table);
    v->sbt_rgen = (VkStridedDeviceAddressRegionKHR){start, region, region};
    v->sbt_miss = (VkStridedDeviceAddressRegionKHR){start + region, rec, region};
    v->sbt_hit = (VkStridedDeviceAddressRegionKHR){start + 2 * region, rec, region};
    v->sbt_call = (VkStridedDeviceAddressRegionKHR){0, 0, 0};
    return ok;
}

bool rt_vk_create(const void *vertices, uint32_t stride, uint32_t n_vertices, const uint32_t *idx,
                  uint32_t n_tris, struct rt_vk **out, struct rt_vk_info *info,
                  struct cv_error *err)
{
    *out = NULL;
    memset(info, 0, sizeof(*info));
    struct rt_vk *v = calloc(1, sizeof(*v));
    if (!make_device(v, info, err) ||
        !make_structures(v, vertices, stride, n_vertices, idx, n_tris, info, err) || !make_pipeline(v, err)) {
        rt_vk_destroy(&v);
        return false;
    }
    *out = v;
    return true;
}

/* Rays and results buffers for n rays, bound to the set. */
static bool ray_buffers(struct rt_vk *v, uint32_t n, struct cv_error *err)
{
    VkDeviceSize rb = (VkDeviceSize)n * 32, ob = (VkDeviceSize)n * 8;
    if (v->rays.b && v->rays.size >= rb)
        return true;
    buf_destroy(v, &v->rays);
    buf_destroy(v, &v->results);
    const VkBufferUsageFlags use = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                   VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    if (!buf_create(v, rb, use, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, &v->rays, "rays", err) ||
        !buf_create(v, ob, use, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, &v->results, "results",
                    err))
        return false;
    VkWriteDescriptorSetAccelerationStructureKHR as = {
        .sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR,
        .accelerationStructureCount = 1,
        .pAccelerationStructures = &v->tlas};
    VkDescriptorBufferInfo bi[2] = {{v->rays.b, 0, VK_WHOLE_SIZE},
                                    {v->results.b, 0, VK_WHOLE_SIZE}};
    VkWriteDescriptorSet w[3] = {
        {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
         .pNext = &as,
         .dstSet = v->set,
         .dstBinding = 0,
         .descriptorCount = 1,
         .descriptorType = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR},
        {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
         .dstSet = v->set,
         .dstBinding = 1,
         .descriptorCount = 1,
         .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
         .pBufferInfo = &bi[0]},
        {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
         .dstSet = v->set,
         .dstBinding = 2,
         .descriptorCount = 1,
         .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
         .pBufferInfo = &bi[1]}};
    vkUpdateDescriptorSets(v->dev, 3, w, 0, NULL);
    return true;
}

bool rt_vk_trace(struct rt_vk *v, const void *rays, uint32_t n, bool any, int repeats,
                 double *ms, uint32_t *results, struct cv_error *err)
{
    if (n == 0) {
        for (int k = 0; k < repeats; k++)
            ms[k] = 0;
        return true;
    }
    if (!ray_buffers(v, n, err) || !transfer(v, &v->rays, rays, NULL, (VkDeviceSize)n * 32, err))
        return false;
    /* rays in index order along x, as GL's 1D dispatch takes them */
    uint32_t w = n <= v->max_launch_x ? n : 65536, h = (n + w - 1) / w;
    uint32_t push[2] = {n, any ? 1u : 0u};
    for (int k = -1; k < repeats; k++) {  /* -1: warm-up, untimed */
        VkCommandBuffer cb;
        if (!cmd_begin(v, &cb, err))
            return false;
        vkCmdResetQueryPool(cb, v->timestamps, 0, 2);
        vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, v->pipeline);
        vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, v->layout, 0, 1,
                                &v->set, 0, NULL);
        vkCmdPushConstants(cb, v->layout, VK_SHADER_STAGE_RAYGEN_BIT_KHR, 0, sizeof(push), push);
        vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, v->timestamps, 0);
        v->cmd_trace_rays(cb, &v->sbt_rgen, &v->sbt_miss, &v->sbt_hit, &v->sbt_call, w, h, 1);
        vkCmdWriteTimestamp(cb, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, v->timestamps, 1);
        double t = 0;
        if (!cmd_run(v, cb, "tracing rays", err) || !read_ms(v, &t, err))
            return false;
        if (k >= 0)
            ms[k] = t;
    }
    return transfer(v, &v->results, NULL, results, (VkDeviceSize)n * 8, err);
}

void rt_vk_destroy(struct rt_vk **pv)
{
    struct rt_vk *v = pv ? *pv : NULL;
    if (!v)
        return;
    if (v->dev) {
        vkDeviceWaitIdle(v->dev);
        if (v->pipeline)
            vkDestroyPipeline(v->dev, v->pipeline, NULL);
        if (v->layout)
            vkDestroyPipelineLayout(v->dev, v->layout, NULL);
        if (v->desc_pool)
            vkDestroyDescriptorPool(v->dev, v->desc_pool, NULL);
        if (v->set_layout)
            vkDestroyDescriptorSetLayout(v->dev, v->set_layout, NULL);
        if (v->tlas)
            v->destroy_as(v->dev, v->tlas, NULL);
        if (v->blas)
            v->destroy_as(v->dev, v->blas, NULL);
        struct vbuf *bufs[] = {&v->verts, &v->index, &v->blas_buf, &v->tlas_buf, &v->inst_buf,
                               &v->sbt, &v->rays, &v->results};
        for (size_t i = 0; i < sizeof(bufs) / sizeof(bufs[0]); i++)
            buf_destroy(v, bufs[i]);
        if (v->timestamps)
            vkDestroyQueryPool(v->dev, v->timestamps, NULL);
        if (v->pool)
            vkDestroyCommandPool(v->dev, v->pool, NULL);
        vkDestroyDevice(v->dev, NULL);
    }
    if (v->inst)
        vkDestroyInstance(v->inst, NULL);
    free(v);
    *pv = NULL;
}
