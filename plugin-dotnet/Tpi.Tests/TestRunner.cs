// A small runner for the NUnit-attributed tests of this assembly, so the suite runs with
// nothing but Mono and nunit.framework.dll (Debian's nunit-console can run the same assembly).
// Runs every [Test] method of every [TestFixture] class ([SetUp]/[TearDown] included), prints
// one PASS/FAIL line per test and closes with the line "N passed, N failed"; exits 1 on any
// failure. Arguments: optional substrings; only tests whose full name contains one of them run.
// Fixtures of category "Benchmark" run after all others.
using System;
using System.Diagnostics;
using System.Linq;
using System.Reflection;
using NUnit.Framework;

namespace Tpi.Tests
{
    public static class TestRunner
    {
        public static int Main(string[] args)
        {
            int passed = 0, failed = 0;
            var fixtures = typeof(TestRunner).Assembly.GetTypes()
                .Where(t => t.GetCustomAttributes(typeof(TestFixtureAttribute), false).Length > 0)
                // Fixtures of category "Benchmark" last: their large meshes would otherwise change
                // the memory baseline of the leak measurement (LeakTests' RSS control).
                .OrderBy(t => IsBenchmark(t) ? 1 : 0)
                .ThenBy(t => t.FullName, StringComparer.Ordinal);
            foreach (var fixture in fixtures)
            {
                var methods = fixture.GetMethods(BindingFlags.Public | BindingFlags.Instance);
                var setUp = methods.FirstOrDefault(m => m.GetCustomAttributes(typeof(SetUpAttribute), false).Length > 0);
                var tearDown = methods.FirstOrDefault(m => m.GetCustomAttributes(typeof(TearDownAttribute), false).Length > 0);
                var tests = methods.Where(m => m.GetCustomAttributes(typeof(TestAttribute), false).Length > 0)
                    .OrderBy(m => m.MetadataToken);
                foreach (var test in tests)
                {
                    var name = fixture.Name + "." + test.Name;
                    if (args.Length > 0 && !args.Any(a => name.Contains(a))) continue;
                    var watch = Stopwatch.StartNew();
                    string failure = null;
                    object instance = null;
                    try
                    {
                        instance = Activator.CreateInstance(fixture);
                        if (setUp != null) setUp.Invoke(instance, null);
                        test.Invoke(instance, null);
                    }
                    catch (TargetInvocationException e)
                    {
                        failure = Describe(e.InnerException);
                    }
                    catch (Exception e)
                    {
                        failure = Describe(e);
                    }
                    finally
                    {
                        if (instance != null && tearDown != null)
                        {
                            try { tearDown.Invoke(instance, null); }
                            catch (Exception e) { if (failure == null) failure = "TearDown: " + Describe(e is TargetInvocationException ? e.InnerException : e); }
                        }
                        var disposable = instance as IDisposable;
                        if (disposable != null) disposable.Dispose();
                    }
                    if (failure == null)
                    {
                        passed++;
                        Console.WriteLine("PASS  {0} ({1} ms)", name, watch.ElapsedMilliseconds);
                    }
                    else
                    {
                        failed++;
                        Console.WriteLine("FAIL  {0}\n      {1}", name, failure.Replace("\n", "\n      "));
                    }
                }
            }
            Console.WriteLine("{0} passed, {1} failed", passed, failed);
            return failed == 0 && passed > 0 ? 0 : 1;
        }

        static bool IsBenchmark(Type fixture)
        {
            return fixture.GetCustomAttributes(typeof(CategoryAttribute), false).Cast<CategoryAttribute>().Any(c => c.Name == "Benchmark");
        }

        static string Describe(Exception e)
        {
            if (e is AssertionException) return e.Message.Trim();
            return e.GetType().Name + ": " + e.Message + "\n" + e.StackTrace;
        }
    }
}
