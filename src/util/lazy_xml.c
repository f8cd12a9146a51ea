/* libxml2's table of functions, loaded on first use (util/lazy_xml.h). */
#include "util/lazy_xml.h"

LAZY_LIB_GETTER(XmlApi, xml_api, "libxml2.so.2", "reading and writing XML (Arbaro and Helios species files, XML tables)",
                false, XML_FUNCS)

/* The library's xmlFree, a variable: found by name once the library is loaded. */
static xmlFreeFunc *xml_free_var;
static pthread_once_t xml_free_once = PTHREAD_ONCE_INIT;
static void xml_free_find(void) {
    xml_api();
    xml_free_var = lazy_lib_sym(&xml_api_lib, "xmlFree");
}
xmlFreeFunc *xml_free(void) {
    pthread_once(&xml_free_once, xml_free_find);
    return xml_free_var;
}
