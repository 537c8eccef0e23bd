// TEMPORARY placeholder, replaced by the atrium builder's texture generators.
#pragma once
