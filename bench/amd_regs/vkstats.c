/* bench/amd_regs/vkstats.c: compiles a compute SPIR-V module with the
 * first Vulkan device (stats.sh picks RADV's null navi21 device) and
 * prints its pipeline executable statistics, one "name: value" a line
 * (VK_KHR_pipeline_executable_properties). LAYOUT lists the module's
 * descriptors, one "set binding ubo|ssbo|tex" a line (remap.py writes it).
 *   usage: vkstats MODULE.spv LAYOUT */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <vulkan/vulkan.h>

static int fail(const char *what, VkResult r)
{
    fprintf(stderr, "vkstats: %s: VkResult %d\n", what, (int)r);
    return 1;
}

static uint32_t *read_module(const char *path, size_t *size)
{
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return NULL;
    uint32_t *code = NULL;
    long n = fseek(fp, 0, SEEK_END) == 0 ? ftell(fp) : -1;
    if (n > 0 && n % 4 == 0 && fseek(fp, 0, SEEK_SET) == 0) {
        code = malloc((size_t)n);
        if (code && fread(code, 1, (size_t)n, fp) != (size_t)n) {
            free(code);
            code = NULL;
        }
    }
    fclose(fp);
    *size = (size_t)n;
    return code;
}

/* Three sets (0 storage buffers, 1 uniform buffers, 2 texel buffers). */
static int read_layout(const char *path, VkDescriptorSetLayoutBinding bl[3][64], uint32_t nb[3])
{
    FILE *fp = fopen(path, "r");
    if (!fp)
        return -1;
    int set, bind;
    char ty[16];
    while (fscanf(fp, "%d %d %15s", &set, &bind, ty) == 3) {
        if (set < 0 || set > 2 || nb[set] == 64)
            continue;
        VkDescriptorType t = strcmp(ty, "ubo") == 0    ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER
                             : strcmp(ty, "ssbo") == 0 ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER
                                                       : VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
        bl[set][nb[set]++] = (VkDescriptorSetLayoutBinding){
            .binding = (uint32_t)bind, .descriptorType = t, .descriptorCount = 1,
            .stageFlags = VK_SHADER_STAGE_COMPUTE_BIT};
    }
    fclose(fp);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: vkstats MODULE.spv LAYOUT\n");
        return 2;
    }
    size_t size = 0;
    uint32_t *code = read_module(argv[1], &size);
    VkDescriptorSetLayoutBinding bl[3][64];
    uint32_t nb[3] = {0, 0, 0};
    if (!code || read_layout(argv[2], bl, nb) != 0) {
        fprintf(stderr, "vkstats: cannot read %s or %s\n", argv[1], argv[2]);
        return 1;
    }
    VkResult r;
    VkApplicationInfo ai = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO, .apiVersion = VK_API_VERSION_1_2};
    VkInstanceCreateInfo ici = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO, .pApplicationInfo = &ai};
    VkInstance inst;
    if ((r = vkCreateInstance(&ici, NULL, &inst)) != VK_SUCCESS)
        return fail("creating the instance", r);
    uint32_t np = 1;
    VkPhysicalDevice pd;
    r = vkEnumeratePhysicalDevices(inst, &np, &pd);
    if ((r != VK_SUCCESS && r != VK_INCOMPLETE) || np == 0)
        return fail("finding a device", r);
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(pd, &props);
    fprintf(stderr, "device: %s\n", props.deviceName);

    float prio = 1;
    VkDeviceQueueCreateInfo qci = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO, .queueCount = 1,
                                   .pQueuePriorities = &prio};
    VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR pef = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR,
        .pipelineExecutableInfo = VK_TRUE};
    const char *ext[] = {"VK_KHR_pipeline_executable_properties"};
    VkDeviceCreateInfo dci = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, .pNext = &pef,
                              .queueCreateInfoCount = 1, .pQueueCreateInfos = &qci,
                              .enabledExtensionCount = 1, .ppEnabledExtensionNames = ext};
    VkDevice dev;
    if ((r = vkCreateDevice(pd, &dci, NULL, &dev)) != VK_SUCCESS)
        return fail("creating the device", r);

    VkShaderModuleCreateInfo smci = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO, .codeSize = size,
                                     .pCode = code};
    VkShaderModule sm;
    if ((r = vkCreateShaderModule(dev, &smci, NULL, &sm)) != VK_SUCCESS)
        return fail("creating the module", r);
    VkDescriptorSetLayout dsl[3];
    for (int i = 0; i < 3; i++) {
        VkDescriptorSetLayoutCreateInfo dlci = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                                .bindingCount = nb[i], .pBindings = bl[i]};
        if ((r = vkCreateDescriptorSetLayout(dev, &dlci, NULL, &dsl[i])) != VK_SUCCESS)
            return fail("creating a set layout", r);
    }
    VkPipelineLayoutCreateInfo plci = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                       .setLayoutCount = 3, .pSetLayouts = dsl};
    VkPipelineLayout pl;
    if ((r = vkCreatePipelineLayout(dev, &plci, NULL, &pl)) != VK_SUCCESS)
        return fail("creating the pipeline layout", r);
    VkComputePipelineCreateInfo cpci = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .flags = VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR,
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                  .stage = VK_SHADER_STAGE_COMPUTE_BIT, .module = sm, .pName = "main"},
        .layout = pl};
    VkPipeline pipe;
    if ((r = vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &cpci, NULL, &pipe)) != VK_SUCCESS)
        return fail("compiling the pipeline", r);

    PFN_vkGetPipelineExecutableStatisticsKHR get_stats =
        (PFN_vkGetPipelineExecutableStatisticsKHR)vkGetDeviceProcAddr(dev, "vkGetPipelineExecutableStatisticsKHR");
    VkPipelineExecutableInfoKHR ei = {.sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR, .pipeline = pipe};
    uint32_t ns = 0;
    if (!get_stats || (r = get_stats(dev, &ei, &ns, NULL)) != VK_SUCCESS)
        return fail("reading the statistics", get_stats ? r : VK_ERROR_EXTENSION_NOT_PRESENT);
    VkPipelineExecutableStatisticKHR *st = calloc(ns, sizeof(*st));
    for (uint32_t i = 0; st && i < ns; i++)
        st[i].sType = VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR;
    if (!st || (r = get_stats(dev, &ei, &ns, st)) != VK_SUCCESS)
        return fail("reading the statistics", r);
    for (uint32_t i = 0; i < ns; i++) {
        printf("%s: ", st[i].name);
        switch (st[i].format) {
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR:
            printf("%llu\n", (unsigned long long)st[i].value.u64);
            break;
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR:
            printf("%lld\n", (long long)st[i].value.i64);
            break;
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR:
            printf("%g\n", st[i].value.f64);
            break;
        default:
            printf("%d\n", (int)st[i].value.b32);
        }
    }
    return 0;
}
